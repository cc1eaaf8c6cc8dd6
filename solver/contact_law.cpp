#include "solver/contact_law.h"
#include "solver/cpu_versions.h"
#include "solver/node_contact_law.h"

namespace tessera {

namespace {

// The law over n entries in SIMD lanes; compiled for the baseline CPU and for AVX2 and AVX-512
// machines (chosen at load time).
TESSERA_CPU_VERSIONS
void contactLaw(const ContactLawConstants<ContactReal>& k, const NodeContactBatch& b) {
  const int n = b.count;
  const ContactReal *__restrict nx = b.nx, *__restrict ny = b.ny, *__restrict nz = b.nz, *__restrict depth = b.depth,
               *__restrict area = b.area, *__restrict vx = b.vx, *__restrict vy = b.vy, *__restrict vz = b.vz;
  ContactReal *__restrict ux = b.ux, *__restrict uy = b.uy, *__restrict uz = b.uz, *__restrict fx = b.fx, *__restrict fy = b.fy,
         *__restrict fz = b.fz, *__restrict fn = b.fn, *__restrict stored = b.stored, *__restrict friction = b.friction,
         *__restrict viscous = b.viscous, *__restrict sliding = b.sliding;
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    const SpringUpdate<ContactReal> u = updateSpring(k, nx[i], ny[i], nz[i], depth[i], area[i], vx[i], vy[i], vz[i], ux[i], uy[i], uz[i]);
    const ContactForce<ContactReal> f = contactForce(k, nx[i], ny[i], nz[i], depth[i], area[i], u.normalSpeed, ux[i], uy[i], uz[i]);
    fx[i] = f.fx;
    fy[i] = f.fy;
    fz[i] = f.fz;
    fn[i] = f.fn;
    stored[i] = f.stored;
    friction[i] = u.friction;
    viscous[i] = u.viscous;
    sliding[i] = u.sliding;
  }
}

}  // namespace

void applyContactLaw(const ContactParameters& p, double kn, double kt, double dt, const NodeContactBatch& b) {
  contactLaw(ContactLawConstants<ContactReal>::of(p, kn, kt, dt), b);
}

}  // namespace tessera

#include "solver/contact_law.h"

#include <cmath>

namespace tessera {

namespace {

// The law over n entries, written without branches so that the compiler runs it in SIMD lanes;
// compiled for the baseline CPU and for AVX2 and AVX-512 machines (chosen at load time). This
// file is compiled without floating-point contraction, so every version gives the same bits.
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
void contactLaw(int n, double perNodeNormal, double perAreaNormal, double perNodeTangent, double perAreaTangent,
                double viscosity, double friction, double dt, const double* __restrict nx, const double* __restrict ny,
                const double* __restrict nz, const double* __restrict depth, const double* __restrict area,
                const double* __restrict vx, const double* __restrict vy, const double* __restrict vz,
                double* __restrict ux, double* __restrict uy, double* __restrict uz, double* __restrict fx,
                double* __restrict fy, double* __restrict fz, double* __restrict fnOut, double* __restrict stored,
                double* __restrict dissipatedFriction, double* __restrict dissipatedViscous, double* __restrict sliding) {
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    const double keep = area[i] > 0 ? 1.0 : 0.0;  // 0: facing away, no force, spring or energy
    const double kna = keep * (perNodeNormal + perAreaNormal * area[i]);  // k_n a, or the per-node k
    const double kta = keep * (perNodeTangent + perAreaTangent * area[i]);
    const double vn = vx[i] * nx[i] + vy[i] * ny[i] + vz[i] * nz[i];
    const double elastic = kna * depth[i];
    const double pushed = elastic - viscosity * area[i] * vn;
    const double fn = pushed > 0 ? pushed : 0.0;

    // Turn the spring onto the tangent plane, keeping its length: u = (s - n (n.s)) |s| / |s - n (n.s)|
    // (a spring already in the plane is left as it is: then the ratio is exactly 1).
    const double along = nx[i] * ux[i] + ny[i] * uy[i] + nz[i] * uz[i];
    const double length2 = ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i];
    double tx = ux[i] - along * nx[i], ty = uy[i] - along * ny[i], tz = uz[i] - along * nz[i];
    const double projected2 = tx * tx + ty * ty + tz * tz;
    const double ratio = length2 / (projected2 > 0 ? projected2 : 1.0);  // every operation in every lane:
    const double turn = std::sqrt(projected2 > 0 ? ratio : 1.0);           // then the lanes choose
    tx *= turn;
    ty *= turn;
    tz *= turn;
    // u = turned + v_t dt; f_t = -k_t a u.
    const double dx = (vx[i] - vn * nx[i]) * dt, dy = (vy[i] - vn * ny[i]) * dt, dz = (vz[i] - vn * nz[i]) * dt;
    double sx = tx + dx, sy = ty + dy, sz = tz + dz;
    double ftx = -kta * sx, fty = -kta * sy, ftz = -kta * sz;
    const double cap = friction * fn, ft2 = ftx * ftx + fty * fty + ftz * ftz;
    // Sliding: f_t and u scaled back to the Coulomb cap (u = -f_t / k_t a). Dissipated: the work
    // put into the spring over the increment (trapezoidal, as a sticking spring stores it
    // exactly) less what it now stores: k_t a (u_0 + u) / 2 . du - k_t a (|u|^2 - |u_0|^2) / 2.
    const bool slides = ft2 > cap * cap;
    const double capped = cap / std::sqrt(ft2 > 0 ? ft2 : 1.0);
    const double scale = slides ? capped : 1.0;
    ftx *= scale;
    fty *= scale;
    ftz *= scale;
    sx *= scale;
    sy *= scale;
    sz *= scale;
    const double u2 = sx * sx + sy * sy + sz * sz, turned2 = tx * tx + ty * ty + tz * tz;
    const double work = 0.5 * ((tx + sx) * dx + (ty + sy) * dy + (tz + sz) * dz);
    dissipatedFriction[i] = slides ? kta * (work - 0.5 * (u2 - turned2)) : 0.0;
    sliding[i] = slides ? 1.0 : 0.0;
    ux[i] = keep * sx;
    uy[i] = keep * sy;
    uz[i] = keep * sz;
    // The non-elastic part of the normal force, f_n - k_n a d, does the work (f_n - k_n a d) v_n dt.
    dissipatedViscous[i] = (elastic - fn) * vn * dt;
    stored[i] = 0.5 * elastic * depth[i] + 0.5 * kta * u2;
    fnOut[i] = fn;
    fx[i] = fn * nx[i] + ftx;
    fy[i] = fn * ny[i] + fty;
    fz[i] = fn * nz[i] + ftz;
  }
}

}  // namespace

void applyContactLaw(const ContactParameters& p, double kn, double kt, double dt, const NodeContactBatch& b) {
  const bool perNode = p.perNodeStiffness > 0;
  contactLaw(b.count, perNode ? p.perNodeStiffness : 0.0, perNode ? 0.0 : kn,
             perNode ? p.tangentialRatio * p.perNodeStiffness : 0.0, perNode ? 0.0 : kt, p.normalViscosity, p.friction, dt,
             b.nx, b.ny, b.nz, b.depth, b.area, b.vx, b.vy, b.vz, b.ux, b.uy, b.uz, b.fx, b.fy, b.fz, b.fn, b.stored,
             b.friction, b.viscous, b.sliding);
}

}  // namespace tessera

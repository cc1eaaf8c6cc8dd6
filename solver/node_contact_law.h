#pragma once
// The contact law of one node contact, inline, for the loops that run it in SIMD lanes
// (solver/contact_law.cpp, solver/pair_contacts.cpp), in the precision Real they run in
// (ContactReal). The law itself: solver/contact_law.h, docs/physics.md "Contact law".
#include "solver/contact_parameters.h"

#include <cmath>

namespace tessera {

/// The law's constants for one pair, in the precision the law runs in (Real: ContactReal in the
/// solver): k_n a = perNodeNormal + perAreaNormal a (N/m; one of the two is 0), k_t a likewise, the
/// normal viscosity (Pa s/m), mu and the step (s).
template <class Real>
struct ContactLawConstants {
  Real perNodeNormal, perAreaNormal, perNodeTangent, perAreaTangent, viscosity, friction, dt;
  static ContactLawConstants of(const ContactParameters& p, double kn, double kt, double dt) {
    const bool perNode = p.perNodeStiffness > 0;
    const auto real = [](double v) { return static_cast<Real>(v); };
    return {real(perNode ? p.perNodeStiffness : 0.0), real(perNode ? 0.0 : kn),
            real(perNode ? p.tangentialRatio * p.perNodeStiffness : 0.0), real(perNode ? 0.0 : kt),
            real(p.normalViscosity), real(p.friction), real(dt)};
  }
};

/// The normal force of one contact at the normal speed v_n = v . n (positive while the sides
/// separate): f_n = k_n a d - eta_n a v_n clipped at 0, with its elastic part k_n a d, and k_t a
/// (0 for a node facing away, area 0).
template <class Real>
struct NormalForce {
  Real kna, kta, elastic, fn;
};
template <class Real>
__attribute__((always_inline)) inline NormalForce<Real> normalForce(const ContactLawConstants<Real>& k, Real depth, Real area,
                                                                    Real vn) {
  NormalForce<Real> f;
  const Real keep = area > 0 ? Real(1) : Real(0);  // 0: facing away, no force, spring or energy
  f.kna = keep * (k.perNodeNormal + k.perAreaNormal * area);  // k_n a, or the per-node k
  f.kta = keep * (k.perNodeTangent + k.perAreaTangent * area);
  f.elastic = f.kna * depth;
  const Real pushed = f.elastic - k.viscosity * area * vn;
  f.fn = pushed > 0 ? pushed : Real(0);
  return f;
}

/// What the update of a contact's tangential spring dissipated: J by sliding, 1 if it slid, the
/// normal speed v_n = v . n (m/s; positive while separating) that contactForce takes, the normal
/// force f_n (N) and what the normal viscosity dissipated this step, (k_n a d - f_n) v_n dt (J).
template <class Real>
struct SpringUpdate {
  Real friction, sliding, normalSpeed, normal, viscous;
};

/// The spring's trial value for one contact, in place: its tangential spring u turned onto the
/// tangent plane of normal n, keeping its length (t), plus the tangential increment v_t dt (v_n =
/// v . n given); t . (t + v_t dt), which capSpring takes. Without branches, so that a loop over
/// contacts runs it in SIMD lanes.
template <class Real>
__attribute__((always_inline)) inline Real trialSpring(const ContactLawConstants<Real>& k, Real nx, Real ny, Real nz, Real vx,
                                                       Real vy, Real vz, Real vn, Real& ux, Real& uy, Real& uz) {
  // Turn the spring onto the tangent plane, keeping its length: u = (s - n (n.s)) |s| / |s - n (n.s)|
  // (a spring already in the plane is left as it is: then the ratio is exactly 1).
  const Real along = nx * ux + ny * uy + nz * uz;
  const Real length2 = ux * ux + uy * uy + uz * uz;
  Real tx = ux - along * nx, ty = uy - along * ny, tz = uz - along * nz;
  const Real projected2 = tx * tx + ty * ty + tz * tz;
  const Real ratio = length2 / (projected2 > 0 ? projected2 : Real(1));  // every operation in every lane:
  const Real turn = std::sqrt(projected2 > 0 ? ratio : Real(1));           // then the lanes choose
  tx *= turn;
  ty *= turn;
  tz *= turn;
  // The trial spring t + v_t dt.
  ux = tx + (vx - vn * nx) * k.dt;
  uy = ty + (vy - vn * ny) * k.dt;
  uz = tz + (vz - vn * nz) * k.dt;
  return tx * ux + ty * uy + tz * uz;
}

/// The spring after its trial (trialSpring, which gave t . s for the trial s in u), in place: cut
/// back to the Coulomb cap |k_t a u| <= mu f_n, and 0 for a node facing away (area 0); what it
/// dissipated. Without branches.
template <class Real>
__attribute__((always_inline)) inline SpringUpdate<Real> capSpring(const ContactLawConstants<Real>& k, Real depth, Real area,
                                                                   Real vn, Real turnedDotTrial, Real& ux, Real& uy, Real& uz) {
  const NormalForce<Real> n = normalForce(k, depth, area, vn);
  const Real trial2 = ux * ux + uy * uy + uz * uz;
  const Real cap = k.friction * n.fn, ft2 = n.kta * n.kta * trial2;  // |k_t a s|^2
  // Sliding: u scaled back to the Coulomb cap, u = c s with |k_t a u| = mu f_n. Dissipated: the
  // work put into the spring over the increment (trapezoidal, as a sticking spring stores it
  // exactly) less what it now stores, k_t a (t + u) / 2 . du - k_t a (|u|^2 - |t|^2) / 2 (t: the
  // turned spring, du = v_t dt), which with u = c (t + du) = c s is k_t a (1 - c) (t . s + c |s|^2)
  // / 2: fewer operations, exactly 0 when sticking (c = 1); either form rounds to about
  // eps k_t a |u|^2.
  const bool slides = ft2 > cap * cap;
  const Real capped = cap / std::sqrt(ft2 > 0 ? ft2 : Real(1));
  const Real scale = slides ? capped : Real(1);
  const Real dissipated = Real(0.5) * n.kta * (Real(1) - scale) * (turnedDotTrial + scale * trial2);
  const Real keep = area > 0 ? scale : Real(0);
  ux *= keep;
  uy *= keep;
  uz *= keep;
  // The non-elastic part of the normal force, f_n - k_n a d, does the work (f_n - k_n a d) v_n dt.
  return {dissipated, slides ? Real(1) : Real(0), vn, n.fn, (n.elastic - n.fn) * vn * k.dt};
}

/// The first part of the law for one contact: its tangential spring u, in place (normal n, depth,
/// area, relative velocity v): trialSpring, then capSpring. Without branches, so that a loop over
/// contacts runs it in SIMD lanes.
template <class Real>
__attribute__((always_inline)) inline SpringUpdate<Real> updateSpring(const ContactLawConstants<Real>& k, Real nx, Real ny,
                                                                      Real nz, Real depth, Real area, Real vx, Real vy,
                                                                      Real vz, Real& ux, Real& uy, Real& uz) {
  const Real vn = vx * nx + vy * ny + vz * nz;
  const Real turnedDotTrial = trialSpring(k, nx, ny, nz, vx, vy, vz, vn, ux, uy, uz);
  return capSpring(k, depth, area, vn, turnedDotTrial, ux, uy, uz);
}

/// What one node contact gives with its spring updated (updateSpring, which gave v_n): its force on the node's
/// body f = f_n n - k_t a u (N), f_n (N) and its stored energy 1/2 k_n a d^2 + 1/2 k_t a |u|^2 (J).
template <class Real>
struct ContactForce {
  Real fx, fy, fz, fn, stored;
};
template <class Real>
__attribute__((always_inline)) inline ContactForce<Real> contactForce(const ContactLawConstants<Real>& k, Real nx, Real ny,
                                                                      Real nz, Real depth, Real area, Real vn, Real ux,
                                                                      Real uy, Real uz) {
  const NormalForce<Real> n = normalForce(k, depth, area, vn);
  ContactForce<Real> f;
  f.fn = n.fn;
  f.fx = n.fn * nx - n.kta * ux;
  f.fy = n.fn * ny - n.kta * uy;
  f.fz = n.fn * nz - n.kta * uz;
  f.stored = Real(0.5) * n.elastic * depth + Real(0.5) * n.kta * (ux * ux + uy * uy + uz * uz);
  return f;
}

}  // namespace tessera

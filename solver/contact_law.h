#pragma once
#include "solver/contact_parameters.h"

#include <cmath>


namespace tessera {

/// What the node contacts of a pair add up to over one step (docs/physics.md, "Energy balance").
struct ContactTally {
  double elastic = 0.0;   ///< J, stored: 1/2 k_n a d^2 + 1/2 k_t a |u|^2
  double friction = 0.0;  ///< J, dissipated by sliding this step (the spring cut back to the Coulomb cap)
  double viscous = 0.0;   ///< J, dissipated by the normal viscosity this step: (k_n a d - f_n) v_n dt
  /// J, stored energy removed (negative: added) by changes of the nodes' projected areas
  /// a max(0, -n_i . n), which the forces do not derive from: the contact normal turning relative
  /// to the node, most where the other body's nearest face switches at an edge and the projection
  /// drops to zero with the node still inside (docs/physics.md, "Energy balance").
  double projection = 0.0;
  int sliding = 0;        ///< node contacts at the Coulomb cap
};

/// Node contacts evaluated together by the contact law: entries 0 .. count-1, one per node contact,
/// each quantity in its own array (world frame, SI units; the arrays belong to the caller), so
/// that the law runs over the contacts in SIMD lanes.
struct NodeContactBatch {
  int count = 0;
  // In.
  const double *nx, *ny, *nz;  ///< unit contact normal: out of the other body, towards the node's body
  const double* depth;         ///< m, penetration d > 0
  const double* area;          ///< m^2, the node's effective area a (docs/physics.md); 0: facing away
  const double *vx, *vy, *vz;  ///< m/s, relative velocity at the node: node's body minus the other
  // In and out: the tangential spring u (m), carried from step to step.
  double *ux, *uy, *uz;
  // Out.
  double *fx, *fy, *fz;  ///< N, force on the node's body
  double* fn;            ///< N, its normal part f . n
  double* stored;        ///< J, the contact's stored energy
  double* friction;      ///< J, dissipated by sliding this step
  double* viscous;       ///< J, dissipated by the normal viscosity this step
  double* sliding;       ///< 1 at the Coulomb cap, else 0
};

/// The contact law over entries 0 .. count-1 of a batch (docs/physics.md, "Contact law"): the force on each node's body and
/// the update of its tangential spring,
///   f_n = k_n a d - eta_n a v_n, clipped at 0             (traction-based normal force)
///   u  <- u projected on the tangent plane, length kept   (history follows the contact frame)
///   u  <- u + v_t dt;  f_t = -k_t a u;  |f_t| <= mu f_n    (elastic spring capped by Coulomb; on
///                                                          sliding the spring is reset to the cap)
/// with its stored energy 1/2 k_n a d^2 + 1/2 k_t a |u|^2 and what it dissipated. kn and kt in
/// N/m^3; with a per-node stiffness k (perNodeStiffness > 0) the products k_n a and k_t a become k
/// and (k_t/k_n) k. An entry with area 0 (a node inside but facing away from the contact normal)
/// gets no force, no spring and no energy. Each entry is computed on its own, by the same
/// operations whatever the CPU's vector width (no fused multiply-add).
void applyContactLaw(const ContactParameters& p, double kn, double kt, double dt, const NodeContactBatch& batch);

/// The law's constants for one pair: k_n a = perNodeNormal + perAreaNormal a (N/m; one of the two
/// is 0), k_t a likewise, the normal viscosity (Pa s/m), mu and the step (s).
struct ContactLawConstants {
  double perNodeNormal, perAreaNormal, perNodeTangent, perAreaTangent, viscosity, friction, dt;
  static ContactLawConstants of(const ContactParameters& p, double kn, double kt, double dt) {
    const bool perNode = p.perNodeStiffness > 0;
    return {perNode ? p.perNodeStiffness : 0.0, perNode ? 0.0 : kn, perNode ? p.tangentialRatio * p.perNodeStiffness : 0.0,
            perNode ? 0.0 : kt, p.normalViscosity, p.friction, dt};
  }
};

/// What the law gives one node contact (the outputs of NodeContactBatch but the spring).
struct NodeContactForce {
  double fx, fy, fz;  ///< N, on the node's body
  double fn;          ///< N, f . n
  double stored;      ///< J
  double friction;    ///< J, dissipated by sliding this step
  double viscous;     ///< J, dissipated by the normal viscosity this step
  double sliding;     ///< 1 at the Coulomb cap, else 0
};

/// The first part of the law for one contact: its spring u turned onto the tangent plane of the
/// normal n, keeping its length, in place: u = (s - n (n.s)) |s| / |s - n (n.s)| (a spring already
/// in the plane is left as it is: then the ratio is exactly 1). Without branches (SIMD lanes).
__attribute__((always_inline)) inline void turnSpring(double nx, double ny, double nz, double& ux, double& uy, double& uz) {
  const double along = nx * ux + ny * uy + nz * uz;
  const double length2 = ux * ux + uy * uy + uz * uz;
  const double tx = ux - along * nx, ty = uy - along * ny, tz = uz - along * nz;
  const double projected2 = tx * tx + ty * ty + tz * tz;
  const double ratio = length2 / (projected2 > 0 ? projected2 : 1.0);  // every operation in every lane:
  const double turn = std::sqrt(projected2 > 0 ? ratio : 1.0);           // then the lanes choose
  ux = tx * turn;
  uy = ty * turn;
  uz = tz * turn;
}

/// The law's trial state for one contact, its spring u already turned (turnSpring): normal force
/// f_n = k_n a d - eta_n a v_n clipped at 0, the increment v_t dt, the trial spring s = u + v_t dt
/// and its force -k_t a s, and the Coulomb cap mu f_n. Without branches (SIMD lanes).
struct ContactTrial {
  double keep, kna, kta, vn, elastic, fn, dx, dy, dz, sx, sy, sz, ftx, fty, ftz, cap, ft2;
};
__attribute__((always_inline)) inline ContactTrial contactTrial(const ContactLawConstants& k, double nx, double ny, double nz,
                                                                double depth, double area, double vx, double vy,
                                                                double vz, double ux, double uy, double uz) {
  ContactTrial t;
  t.keep = area > 0 ? 1.0 : 0.0;  // 0: facing away, no force, spring or energy
  t.kna = t.keep * (k.perNodeNormal + k.perAreaNormal * area);  // k_n a, or the per-node k
  t.kta = t.keep * (k.perNodeTangent + k.perAreaTangent * area);
  t.vn = vx * nx + vy * ny + vz * nz;
  t.elastic = t.kna * depth;
  const double pushed = t.elastic - k.viscosity * area * t.vn;
  t.fn = pushed > 0 ? pushed : 0.0;
  // s = turned + v_t dt; f_t = -k_t a s.
  t.dx = (vx - t.vn * nx) * k.dt;
  t.dy = (vy - t.vn * ny) * k.dt;
  t.dz = (vz - t.vn * nz) * k.dt;
  t.sx = ux + t.dx;
  t.sy = uy + t.dy;
  t.sz = uz + t.dz;
  t.ftx = -t.kta * t.sx;
  t.fty = -t.kta * t.sy;
  t.ftz = -t.kta * t.sz;
  t.cap = k.friction * t.fn;
  t.ft2 = t.ftx * t.ftx + t.fty * t.fty + t.ftz * t.ftz;
  return t;
}

/// What the trial spring and force are scaled by: 1 when sticking, mu f_n / |f_t| when the trial
/// force passes the Coulomb cap (sliding).
__attribute__((always_inline)) inline double slidingScale(const ContactTrial& t) {
  const bool slides = t.ft2 > t.cap * t.cap;
  const double capped = t.cap / std::sqrt(t.ft2 > 0 ? t.ft2 : 1.0);  // every operation in every lane
  return slides ? capped : 1.0;
}

/// The rest of the law for one contact, its spring u already turned (turnSpring) and updated in
/// place, with `scale` = slidingScale of its trial: normal n, depth, area, relative velocity v.
/// Without branches (SIMD lanes).
__attribute__((always_inline)) inline NodeContactForce turnedContactLaw(const ContactLawConstants& k, double nx, double ny,
                                                                        double nz, double depth, double area, double vx,
                                                                        double vy, double vz, double scale, double& ux,
                                                                        double& uy, double& uz) {
  const ContactTrial t = contactTrial(k, nx, ny, nz, depth, area, vx, vy, vz, ux, uy, uz);
  // Sliding: f_t and u scaled back to the Coulomb cap (u = -f_t / k_t a). Dissipated: the work
  // put into the spring over the increment (trapezoidal, as a sticking spring stores it
  // exactly) less what it now stores: k_t a (u_0 + u) / 2 . du - k_t a (|u|^2 - |u_0|^2) / 2.
  const bool slides = t.ft2 > t.cap * t.cap;
  const double ftx = t.ftx * scale, fty = t.fty * scale, ftz = t.ftz * scale;
  const double sx = t.sx * scale, sy = t.sy * scale, sz = t.sz * scale;
  const double u2 = sx * sx + sy * sy + sz * sz, turned2 = ux * ux + uy * uy + uz * uz;
  const double work = 0.5 * ((ux + sx) * t.dx + (uy + sy) * t.dy + (uz + sz) * t.dz);
  NodeContactForce out;
  out.friction = slides ? t.kta * (work - 0.5 * (u2 - turned2)) : 0.0;
  out.sliding = slides ? 1.0 : 0.0;
  ux = t.keep * sx;
  uy = t.keep * sy;
  uz = t.keep * sz;
  // The non-elastic part of the normal force, f_n - k_n a d, does the work (f_n - k_n a d) v_n dt.
  out.viscous = (t.elastic - t.fn) * t.vn * k.dt;
  out.stored = 0.5 * t.elastic * depth + 0.5 * t.kta * u2;
  out.fn = t.fn;
  out.fx = t.fn * nx + ftx;
  out.fy = t.fn * ny + fty;
  out.fz = t.fn * nz + ftz;
  return out;
}

/// The law of applyContactLaw for one contact (turnSpring, slidingScale, turnedContactLaw): normal n,
/// depth, area, relative velocity v, and its spring u updated in place. Every caller is compiled
/// without floating-point contraction (the same bits everywhere).
__attribute__((always_inline)) inline NodeContactForce nodeContactLaw(const ContactLawConstants& k, double nx, double ny,
                                                                      double nz, double depth, double area, double vx,
                                                                      double vy, double vz, double& ux, double& uy,
                                                                      double& uz) {
  turnSpring(nx, ny, nz, ux, uy, uz);
  const double scale = slidingScale(contactTrial(k, nx, ny, nz, depth, area, vx, vy, vz, ux, uy, uz));
  return turnedContactLaw(k, nx, ny, nz, depth, area, vx, vy, vz, scale, ux, uy, uz);
}

}  // namespace tessera

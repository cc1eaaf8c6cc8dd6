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

/// The normal force of one contact: f_n = k_n a d - eta_n a v_n clipped at 0, with its elastic part
/// k_n a d, the approach speed v_n = v . n, and k_t a (0 for a node facing away, area 0).
struct NormalForce {
  double kna, kta, vn, elastic, fn;
};
__attribute__((always_inline)) inline NormalForce normalForce(const ContactLawConstants& k, double nx, double ny, double nz,
                                                              double depth, double area, double vx, double vy, double vz) {
  NormalForce f;
  const double keep = area > 0 ? 1.0 : 0.0;  // 0: facing away, no force, spring or energy
  f.kna = keep * (k.perNodeNormal + k.perAreaNormal * area);  // k_n a, or the per-node k
  f.kta = keep * (k.perNodeTangent + k.perAreaTangent * area);
  f.vn = vx * nx + vy * ny + vz * nz;
  f.elastic = f.kna * depth;
  const double pushed = f.elastic - k.viscosity * area * f.vn;
  f.fn = pushed > 0 ? pushed : 0.0;
  return f;
}

/// What the update of a contact's tangential spring dissipated: J by sliding, and 1 if it slid.
struct SpringUpdate {
  double friction, sliding;
};

/// The first part of the law for one contact: its tangential spring u, in place (normal n, depth,
/// area, relative velocity v). Without branches, so that a loop over contacts runs it in SIMD
/// lanes; every caller is compiled without floating-point contraction (the same bits everywhere).
__attribute__((always_inline)) inline SpringUpdate updateSpring(const ContactLawConstants& k, double nx, double ny,
                                                                double nz, double depth, double area, double vx,
                                                                double vy, double vz, double& ux, double& uy, double& uz) {
  const NormalForce n = normalForce(k, nx, ny, nz, depth, area, vx, vy, vz);
  // Turn the spring onto the tangent plane, keeping its length: u = (s - n (n.s)) |s| / |s - n (n.s)|
  // (a spring already in the plane is left as it is: then the ratio is exactly 1).
  const double along = nx * ux + ny * uy + nz * uz;
  const double length2 = ux * ux + uy * uy + uz * uz;
  double tx = ux - along * nx, ty = uy - along * ny, tz = uz - along * nz;
  const double projected2 = tx * tx + ty * ty + tz * tz;
  const double ratio = length2 / (projected2 > 0 ? projected2 : 1.0);  // every operation in every lane:
  const double turn = std::sqrt(projected2 > 0 ? ratio : 1.0);           // then the lanes choose
  tx *= turn;
  ty *= turn;
  tz *= turn;
  // u = turned + v_t dt; the trial force -k_t a u.
  const double dx = (vx - n.vn * nx) * k.dt, dy = (vy - n.vn * ny) * k.dt, dz = (vz - n.vn * nz) * k.dt;
  double sx = tx + dx, sy = ty + dy, sz = tz + dz;
  const double ftx = -n.kta * sx, fty = -n.kta * sy, ftz = -n.kta * sz;
  const double cap = k.friction * n.fn, ft2 = ftx * ftx + fty * fty + ftz * ftz;
  // Sliding: u scaled back to the Coulomb cap, |k_t a u| = mu f_n. Dissipated: the work put into
  // the spring over the increment (trapezoidal, as a sticking spring stores it exactly) less what
  // it now stores: k_t a (u_0 + u) / 2 . du - k_t a (|u|^2 - |u_0|^2) / 2.
  const bool slides = ft2 > cap * cap;
  const double capped = cap / std::sqrt(ft2 > 0 ? ft2 : 1.0);
  const double scale = slides ? capped : 1.0;
  sx *= scale;
  sy *= scale;
  sz *= scale;
  const double u2 = sx * sx + sy * sy + sz * sz, turned2 = tx * tx + ty * ty + tz * tz;
  const double work = 0.5 * ((tx + sx) * dx + (ty + sy) * dy + (tz + sz) * dz);
  const double keep = area > 0 ? 1.0 : 0.0;
  ux = keep * sx;
  uy = keep * sy;
  uz = keep * sz;
  return {slides ? n.kta * (work - 0.5 * (u2 - turned2)) : 0.0, slides ? 1.0 : 0.0};
}

/// What one node contact gives with its spring updated (updateSpring): its force on the node's
/// body f = f_n n - k_t a u (N), f_n (N), its stored energy 1/2 k_n a d^2 + 1/2 k_t a |u|^2 (J) and
/// what the normal viscosity dissipated this step, (k_n a d - f_n) v_n dt (J).
struct ContactForce {
  double fx, fy, fz, fn, stored, viscous;
};
__attribute__((always_inline)) inline ContactForce contactForce(const ContactLawConstants& k, double nx, double ny,
                                                                double nz, double depth, double area, double vx,
                                                                double vy, double vz, double ux, double uy, double uz) {
  const NormalForce n = normalForce(k, nx, ny, nz, depth, area, vx, vy, vz);
  ContactForce f;
  f.fn = n.fn;
  f.fx = n.fn * nx - n.kta * ux;
  f.fy = n.fn * ny - n.kta * uy;
  f.fz = n.fn * nz - n.kta * uz;
  f.stored = 0.5 * n.elastic * depth + 0.5 * n.kta * (ux * ux + uy * uy + uz * uz);
  // The non-elastic part of the normal force, f_n - k_n a d, does the work (f_n - k_n a d) v_n dt.
  f.viscous = (n.elastic - n.fn) * n.vn * k.dt;
  return f;
}

}  // namespace tessera

#pragma once
#include "solver/contact_parameters.h"

#include <vector>

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
/// each quantity in its own array (world frame, SI units), so that the law runs over the contacts
/// in SIMD lanes. The arrays only grow: a batch reused step after step allocates nothing.
struct NodeContactBatch {
  int count = 0;
  // In.
  std::vector<double> nx, ny, nz;  ///< unit contact normal: out of the other body, towards the node's body
  std::vector<double> depth;       ///< m, penetration d > 0
  std::vector<double> area;        ///< m^2, the node's effective area a (docs/physics.md)
  std::vector<double> vx, vy, vz;  ///< m/s, relative velocity at the node: node's body minus the other
  // In and out: the tangential spring u (m), carried from step to step.
  std::vector<double> ux, uy, uz;
  // Out.
  std::vector<double> fx, fy, fz;  ///< N, force on the node's body
  std::vector<double> fn;          ///< N, its normal part f . n
  std::vector<double> stored;      ///< J, the contact's stored energy
  std::vector<double> friction;    ///< J, dissipated by sliding this step
  std::vector<double> viscous;     ///< J, dissipated by the normal viscosity this step
  std::vector<double> sliding;     ///< 1 at the Coulomb cap, else 0

  /// Room for n entries (values unset); count unchanged.
  void reserve(int n) {
    if (n > static_cast<int>(depth.size())) grow(n);
  }

 private:
  void grow(int n);
};

/// The contact law over entries 0 .. count-1 of a batch (docs/physics.md, "Contact law"): the force on each node's body and
/// the update of its tangential spring,
///   f_n = k_n a d - eta_n a v_n, clipped at 0             (traction-based normal force)
///   u  <- u projected on the tangent plane, length kept   (history follows the contact frame)
///   u  <- u + v_t dt;  f_t = -k_t a u;  |f_t| <= mu f_n    (elastic spring capped by Coulomb; on
///                                                          sliding the spring is reset to the cap)
/// with its stored energy 1/2 k_n a d^2 + 1/2 k_t a |u|^2 and what it dissipated. kn and kt in
/// N/m^3; with a per-node stiffness k (perNodeStiffness > 0) the products k_n a and k_t a become k
/// and (k_t/k_n) k. Each entry is computed on its own, by the same operations whatever the CPU's
/// vector width (no fused multiply-add), so results do not depend on the machine.
void applyContactLaw(const ContactParameters& p, double kn, double kt, double dt, NodeContactBatch& batch);

}  // namespace tessera

#pragma once
#include "solver/contact_parameters.h"
#include "solver/node_contacts.h"


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
/// each quantity in its own array (world frame, SI units, ContactReal as the solver keeps them; the
/// arrays belong to the caller), so that the law runs over the contacts in SIMD lanes.
struct NodeContactBatch {
  int count = 0;
  // In.
  const ContactReal *nx, *ny, *nz;  ///< unit contact normal: out of the other body, towards the node's body
  const ContactReal* depth;         ///< m, penetration d > 0
  const ContactReal* area;          ///< m^2, the node's effective area a (docs/physics.md); 0: facing away
  const ContactReal *vx, *vy, *vz;  ///< m/s, relative velocity at the node: node's body minus the other
  // In and out: the tangential spring u (m), carried from step to step.
  ContactReal *ux, *uy, *uz;
  // Out.
  ContactReal *fx, *fy, *fz;  ///< N, force on the node's body
  ContactReal* fn;            ///< N, its normal part f . n
  ContactReal* stored;        ///< J, the contact's stored energy
  ContactReal* friction;      ///< J, dissipated by sliding this step
  ContactReal* viscous;       ///< J, dissipated by the normal viscosity this step
  ContactReal* sliding;       ///< 1 at the Coulomb cap, else 0
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
/// gets no force, no spring and no energy. Each entry is computed on its own, in ContactReal: a
/// batch gives each entry the bits it gets alone.
void applyContactLaw(const ContactParameters& p, double kn, double kt, double dt, const NodeContactBatch& batch);

}  // namespace tessera

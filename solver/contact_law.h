#pragma once
#include "solver/contact_parameters.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace tessera {

/// One node in contact, as the contact law sees it.
struct NodeContactInput {
  Eigen::Vector3d normal;            ///< unit, world: out of the other body, towards the node's body
  double depth;                      ///< m, penetration d > 0
  double area;                       ///< m^2, the node's effective area (see docs/physics.md)
  Eigen::Vector3d relativeVelocity;  ///< m/s, node's body minus the other body, at the node
};

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

/// Force (N, world) on the node's body from one node contact, and the update of its tangential
/// spring (m, the elastic tangential displacement, carried from step to step). Sets `stored` to
/// the contact's stored energy and adds it, and what it dissipated, to `tally` (J). Equations (docs/physics.md, "Contact law"):
///   f_n = k_n a d - eta_n a v_n, clipped at 0             (traction-based normal force)
///   u  <- u projected on the tangent plane, length kept   (history follows the contact frame)
///   u  <- u + v_t dt;  f_t = -k_t a u;  |f_t| <= mu f_n    (elastic spring capped by Coulomb; on
///                                                          sliding the spring is reset to the cap)
/// With a per-node stiffness k (perNodeStiffness > 0) the products k_n a and k_t a become k and
/// (k_t/k_n) k.
inline Eigen::Vector3d contactForce(const ContactParameters& p, double kn, double kt, const NodeContactInput& c,
                                    Eigen::Vector3d& spring, double& stored, double dt, ContactTally& tally) {
  const Eigen::Vector3d& n = c.normal;
  const double normalStiffness = p.perNodeStiffness > 0 ? p.perNodeStiffness : kn * c.area;
  const double tangentStiffness = p.perNodeStiffness > 0 ? p.tangentialRatio * p.perNodeStiffness : kt * c.area;
  const double vn = c.relativeVelocity.dot(n);
  const double elastic = normalStiffness * c.depth;
  const double fn = std::max(0.0, elastic - p.normalViscosity * c.area * vn);

  // Turn the spring onto the tangent plane, keeping its length: u = (s - n (n.s)) |s| / |s - n (n.s)|.
  Eigen::Vector3d u = spring;
  const double along = n.dot(spring);
  if (along != 0) {
    const double length2 = spring.squaredNorm();
    u -= along * n;
    const double projected2 = u.squaredNorm();
    if (projected2 > 0) u *= std::sqrt(length2 / projected2);
  }
  const Eigen::Vector3d turned = u, increment = (c.relativeVelocity - vn * n) * dt;
  u += increment;
  Eigen::Vector3d ft = -tangentStiffness * u;
  const double cap = p.friction * fn, ft2 = ft.squaredNorm();
  if (ft2 > cap * cap) {
    // Sliding: f_t and u scaled back to the Coulomb cap (u = -f_t / k_t). Dissipated: the work
    // put into the spring over the increment (trapezoidal, as a sticking spring stores it
    // exactly) less what it now stores: k_t (u_0 + u) / 2 . du - k_t (|u|^2 - |u_0|^2) / 2.
    const double scale = cap / std::sqrt(ft2);
    ft *= scale;
    u *= scale;
    tally.friction += tangentStiffness * (0.5 * (turned + u).dot(increment) - 0.5 * (u.squaredNorm() - turned.squaredNorm()));
    ++tally.sliding;
  }
  spring = u;
  // The non-elastic part of the normal force, f_n - k_n a d, does the work (f_n - k_n a d) v_n dt.
  tally.viscous += (elastic - fn) * vn * dt;
  stored = 0.5 * elastic * c.depth + 0.5 * tangentStiffness * u.squaredNorm();
  tally.elastic += stored;
  return fn * n + ft;
}

}  // namespace tessera

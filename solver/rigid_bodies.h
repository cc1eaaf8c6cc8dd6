#pragma once
#include "levelset/body.h"
#include "levelset/shape.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace tessera {

/// The state of every body, as arrays (hot data). Angular momentum is kept in the body frame
/// (the principal frame), where the inertia tensor is diagonal.
struct RigidBodies {
  std::vector<Eigen::Vector3d> position;         ///< m, world position of the centroid
  std::vector<Eigen::Quaterniond> orientation;   ///< unit, body -> world
  std::vector<Eigen::Vector3d> velocity;         ///< m/s
  std::vector<Eigen::Vector3d> angularMomentum;  ///< kg m^2/s, body frame
  std::vector<double> mass;                      ///< kg
  std::vector<Eigen::Vector3d> inertia;          ///< kg m^2, principal moments (body axes)
  std::vector<char> fixed;                       ///< a support: never integrated (Body::fixed)
  std::vector<char> retired;                     ///< taken out of the computation (World::retireBody): frozen, in no pair
  std::vector<int> shape;                        ///< index into the World's shapes
  std::vector<std::string> name;

  std::size_t size() const { return position.size(); }
  /// Integrated: neither a support nor retired.
  bool moves(std::size_t i) const { return !fixed[i] && !retired[i]; }
  /// omega in the world frame, rad/s.
  Eigen::Vector3d angularVelocity(std::size_t i) const {
    return orientation[i] * angularMomentum[i].cwiseQuotient(inertia[i]);
  }
  double kineticEnergy(std::size_t i) const {
    return 0.5 * mass[i] * velocity[i].squaredNorm() +
           0.5 * angularMomentum[i].cwiseAbs2().cwiseQuotient(inertia[i]).sum();
  }
};

/// How far a rigid turn moves a point at unit distance from its axis: the chord 2 sin(theta / 2)
/// of the angle theta between two orientations, 2 |d.vec| / |d| for the rotation d = q q0^-1
/// (|d.vec| = |d| sin(theta / 2)); exact, below theta, and without a trigonometric call. A point
/// at r from the centroid moves by at most |dp| + turnChord(q, q0) r.
inline double turnChord(const Eigen::Quaterniond& q, const Eigen::Quaterniond& q0) {
  const Eigen::Quaterniond d = q * q0.conjugate();
  return 2 * d.vec().norm() / d.norm();
}

/// What every pair of a step reads of each body's rotation, computed once per step for all its
/// pairs: its rotation matrix (body -> world) and its angular velocity (world, rad/s), the values
/// of orientation[i].toRotationMatrix() and RigidBodies::angularVelocity(i).
struct BodyKinematics {
  std::vector<Eigen::Matrix3d> rotation;
  std::vector<Eigen::Vector3d> angularVelocity;
  void update(const RigidBodies& bodies) {
    rotation.resize(bodies.size());
    angularVelocity.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      rotation[i] = bodies.orientation[i].toRotationMatrix();
      angularVelocity[i] = bodies.angularVelocity(i);
    }
  }
};

/// The bodies placed among `shapes`, at rest: mass = density x volume, inertia = density x
/// principal moments.
RigidBodies makeRigidBodies(const std::vector<Shape>& shapes, const std::vector<Body>& bodies, double density);

/// The torque-free rotation of a rigid body over dt, by the symmetric splitting of the free-rotor
/// Hamiltonian into rotations about the principal axes (Dullweber, Leimkuhler & McLachlan,
/// J. Chem. Phys. 107, 1997): H1(dt/2) H2(dt/2) H3(dt) H2(dt/2) H1(dt/2), where Hk turns the body
/// about its axis k by the angle t Pi_k / I_k and the body-frame momentum Pi the other way.
/// Symplectic and time-reversible; |Pi| and the world angular momentum q Pi are conserved exactly.
/// Turns every body that moves, eight at a time as arrays of their components (each body's
/// result the same as alone): the bodies' chains of dependent operations run side by side.
void rotateFreely(RigidBodies& bodies, double dt);

}  // namespace tessera

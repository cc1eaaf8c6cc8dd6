#include "solver/rigid_bodies.h"

#include <cmath>

namespace tessera {

RigidBodies makeRigidBodies(const Bundle& bundle, double density) {
  RigidBodies b;
  for (const Body& body : bundle.bodies) {
    const Shape& shape = bundle.shapes[body.shape];
    b.position.push_back(body.position);
    b.orientation.push_back(body.orientation.normalized());
    b.velocity.push_back(Eigen::Vector3d::Zero());
    b.angularMomentum.push_back(Eigen::Vector3d::Zero());
    b.mass.push_back(density * shape.mass.volume);
    b.inertia.push_back(density * shape.mass.principalMoments);
    b.fixed.push_back(body.fixed ? 1 : 0);
    b.shape.push_back(body.shape);
    b.name.push_back(body.name);
  }
  return b;
}

namespace {

// Flow of H_k = Pi_k^2 / (2 I_k) for time t: the body turns by phi = t Pi_k / I_k about its axis
// k (q <- q rot_k(phi)) and Pi turns by -phi about the same axis (Pi_k unchanged). One sine and
// cosine, of the half angle (the quaternion's): cos phi = 1 - 2 sin^2(phi/2) and
// sin phi = 2 sin(phi/2) cos(phi/2).
void rotateAboutAxis(int k, Eigen::Quaterniond& q, Eigen::Vector3d& pi, const Eigen::Vector3d& inertia, double t) {
  const double phi = t * pi[k] / inertia[k];
  const double halfCos = std::cos(0.5 * phi), halfSin = std::sin(0.5 * phi);
  const double c = 1 - 2 * halfSin * halfSin, s = 2 * halfSin * halfCos;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double pi_i = pi[i], pi_j = pi[j];
  pi[i] = c * pi_i + s * pi_j;
  pi[j] = -s * pi_i + c * pi_j;
  Eigen::Quaterniond turn(halfCos, 0, 0, 0);
  turn.vec()[k] = halfSin;
  q = q * turn;
}

}  // namespace

void rotateFreely(Eigen::Quaterniond& orientation, Eigen::Vector3d& angularMomentum, const Eigen::Vector3d& inertia,
                  double dt) {
  rotateAboutAxis(0, orientation, angularMomentum, inertia, 0.5 * dt);
  rotateAboutAxis(1, orientation, angularMomentum, inertia, 0.5 * dt);
  rotateAboutAxis(2, orientation, angularMomentum, inertia, dt);
  rotateAboutAxis(1, orientation, angularMomentum, inertia, 0.5 * dt);
  rotateAboutAxis(0, orientation, angularMomentum, inertia, 0.5 * dt);
  orientation.normalize();
}

}  // namespace tessera

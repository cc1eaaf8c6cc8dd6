#include "solver/rigid_bodies.h"

#include <cmath>

namespace tessera {

RigidBodies makeRigidBodies(const std::vector<Shape>& shapes, const std::vector<Body>& bodies, double density) {
  RigidBodies b;
  for (const Body& body : bodies) {
    const Shape& shape = shapes.at(body.shape);
    b.position.push_back(body.position);
    b.orientation.push_back(body.orientation.normalized());
    b.velocity.push_back(Eigen::Vector3d::Zero());
    b.angularMomentum.push_back(Eigen::Vector3d::Zero());
    b.mass.push_back(density * shape.mass.volume);
    b.inertia.push_back(density * shape.mass.principalMoments);
    b.fixed.push_back(body.fixed ? 1 : 0);
    b.retired.push_back(0);
    b.shape.push_back(body.shape);
    b.name.push_back(body.name);
  }
  return b;
}

namespace {

// Bodies turned together, as arrays of their components (lanes): quaternion q = (w, v), body-frame
// angular momentum Pi, principal moments I.
constexpr int kLanes = 8;
struct RotationLanes {
  double w[kLanes], v[3][kLanes], pi[3][kLanes], inertia[3][kLanes];
};

// The sine and cosine of each lane's x; below 1/16 rad (a step turns a body by far less) their
// Taylor series by Horner's rule, the reciprocals as constants: the first left-out terms,
// x^11/11! and x^12/12!, are below 3e-20 of sin x and 1e-23 of cos x, under half an ulp. NaN and
// infinity take the library's path (NaN out, as before: the stability check sees it).
void sinesAndCosines(const double (&x)[kLanes], double (&sine)[kLanes], double (&cosine)[kLanes]) {
  for (int l = 0; l < kLanes; ++l) {
    const double x2 = x[l] * x[l];
    sine[l] = x[l] * (1 - x2 * (1.0 / 6) * (1 - x2 * (1.0 / 20) * (1 - x2 * (1.0 / 42) * (1 - x2 * (1.0 / 72)))));
    cosine[l] = 1 - x2 * 0.5 * (1 - x2 * (1.0 / 12) * (1 - x2 * (1.0 / 30) * (1 - x2 * (1.0 / 56) * (1 - x2 * (1.0 / 90)))));
  }
  for (int l = 0; l < kLanes; ++l)
    if (!(std::abs(x[l]) < 0.0625)) {
      sine[l] = std::sin(x[l]);
      cosine[l] = std::cos(x[l]);
    }
}

// Flow of H_k = Pi_k^2 / (2 I_k) for time t: the body turns by phi = t Pi_k / I_k about its axis
// k (q <- q r, r = (cos(phi/2), sin(phi/2) e_k)) and Pi turns by -phi about the same axis (Pi_k
// unchanged). One sine and cosine, of the half angle: cos phi = 1 - 2 sin^2(phi/2) and
// sin phi = 2 sin(phi/2) cos(phi/2). With (i, j, k) cyclic, q r = (c w - s v_k, v') where
// v'_i = c v_i + s v_j, v'_j = c v_j - s v_i, v'_k = c v_k + s w (c, s: the half angle's).
template <int k>
void rotateAboutAxis(RotationLanes& b, double t) {
  constexpr int i = (k + 1) % 3, j = (k + 2) % 3;
  double half[kLanes], hs[kLanes], hc[kLanes];
  for (int l = 0; l < kLanes; ++l) half[l] = 0.5 * (t * b.pi[k][l] / b.inertia[k][l]);
  sinesAndCosines(half, hs, hc);
  for (int l = 0; l < kLanes; ++l) {
    const double c = 1 - 2 * hs[l] * hs[l], s = 2 * hs[l] * hc[l];
    const double pi_i = b.pi[i][l], pi_j = b.pi[j][l];
    b.pi[i][l] = c * pi_i + s * pi_j;
    b.pi[j][l] = -s * pi_i + c * pi_j;
    const double w = b.w[l], vi = b.v[i][l], vj = b.v[j][l], vk = b.v[k][l];
    b.w[l] = hc[l] * w - hs[l] * vk;
    b.v[i][l] = hc[l] * vi + hs[l] * vj;
    b.v[j][l] = hc[l] * vj - hs[l] * vi;
    b.v[k][l] = hc[l] * vk + hs[l] * w;
  }
}

}  // namespace

void rotateFreely(RigidBodies& bodies, double dt) {
  std::size_t next = 0;
  while (true) {
    // Up to kLanes free bodies; unused lanes turn a body at rest.
    std::size_t body[kLanes];
    int used = 0;
    for (; next < bodies.size() && used < kLanes; ++next)
      if (bodies.moves(next)) body[used++] = next;
    if (used == 0) return;
    RotationLanes b;
    for (int l = 0; l < kLanes; ++l) {
      const bool real = l < used;
      const Eigen::Quaterniond q = real ? bodies.orientation[body[l]] : Eigen::Quaterniond::Identity();
      b.w[l] = q.w();
      for (int a = 0; a < 3; ++a) {
        b.v[a][l] = q.vec()[a];
        b.pi[a][l] = real ? bodies.angularMomentum[body[l]][a] : 0.0;
        b.inertia[a][l] = real ? bodies.inertia[body[l]][a] : 1.0;
      }
    }
    rotateAboutAxis<0>(b, 0.5 * dt);
    rotateAboutAxis<1>(b, 0.5 * dt);
    rotateAboutAxis<2>(b, dt);
    rotateAboutAxis<1>(b, 0.5 * dt);
    rotateAboutAxis<0>(b, 0.5 * dt);
    double norm[kLanes];
    for (int l = 0; l < kLanes; ++l) norm[l] = std::sqrt(b.w[l] * b.w[l] + b.v[0][l] * b.v[0][l] + b.v[1][l] * b.v[1][l] + b.v[2][l] * b.v[2][l]);
    for (int l = 0; l < used; ++l) {
      bodies.orientation[body[l]] = Eigen::Quaterniond(b.w[l] / norm[l], b.v[0][l] / norm[l], b.v[1][l] / norm[l], b.v[2][l] / norm[l]);
      bodies.angularMomentum[body[l]] = Eigen::Vector3d(b.pi[0][l], b.pi[1][l], b.pi[2][l]);
    }
  }
}

}  // namespace tessera

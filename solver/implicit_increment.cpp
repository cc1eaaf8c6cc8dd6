// The implicit method (docs/physics.md, "Implicit method"): each increment of duration dt finds
// the free bodies' poses at its end for which the forces balance, with backward Euler's inertia,
//   F_c(q) + m g - m (dx / dt - v_0) / dt = 0,   T_c(q) - I_0 (dtheta / dt - omega_0) / dt = 0,
// by Newton's method over six unknowns per free body (dx, and dtheta, the rotation vector of
// q q_0^-1), the tangent assembled from each pair's contact stiffness (implicit_contacts.h) and
// factorised sparse (Eigen's SparseLU, in numberFreeBodies' order), with a backtracking line
// search. Where the increment is long against a body's periods the inertia terms vanish against
// the contact forces and the balance is static; where no static balance exists (a block losing
// its support) they carry the motion as backward-Euler dynamics. An increment that does not
// converge is cut to a quarter and tried again from the same start; an easy one lets the next
// grow. Friction history, energies and forces are committed only at a converged increment.
#include "solver/world_internals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace tessera {

namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

// The rotation vector of q q0^-1 (angle x axis), rad.
Eigen::Vector3d rotationBetween(const Eigen::Quaterniond& q, const Eigen::Quaterniond& q0) {
  const Eigen::AngleAxisd turn(q * q0.conjugate());
  return turn.angle() * turn.axis();
}

// q turned by the rotation vector theta (world), normalised.
Eigen::Quaterniond turned(const Eigen::Quaterniond& q, const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  if (!(angle > 0)) return q;
  return (Eigen::Quaterniond(Eigen::AngleAxisd(angle, theta / angle)) * q).normalized();
}

// A pair's committed contacts (the increment's start), found by (a, b) in the sorted copy.
const NodeContacts& committedOf(const std::vector<PairContacts>& committed, const PairContacts& pair) {
  static const NodeContacts none;
  const auto found = std::lower_bound(committed.begin(), committed.end(), pair, pairsByBodies);
  return found != committed.end() && found->a == pair.a && found->b == pair.b && found->kind == pair.kind ? found->contacts : none;
}

// Step lengths 1, 1/2, 1/4: a correction that no length lowers the merit is mostly one across a
// change of the law's active set, which shorter steps do not mend; two halvings took 0.85 x the
// evaluations of four on the default test (docs/performance.md, "The implicit method").
constexpr int kLineSearchHalvings = 2;
constexpr int kEasyIterations = 4;      // an increment converged in this many lets the next double
constexpr double kStepLimitRatio = 0.05;  // of the thinnest block: the farthest one iteration moves a point
constexpr double kCandidateBandRatio = 0.01;  // of the thinnest block: ImplicitCandidates' band
constexpr double kFirstIncrementRatio = 100;  // x the explicit automatic step: the first increment

std::string format(const char* pattern, double a, double b = 0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, a, b);
  return buffer;
}

}  // namespace

// s, the settings' longest increment (0: 1e4 explicit automatic steps).
double World::implicitLongestIncrement() const {
  return settings_.implicit.maxIncrement > 0 ? settings_.implicit.maxIncrement : 1e4 * automaticDt_;
}

// s, the longest increment allowed now: implicitLongestIncrement, and the time in which the
// fastest obstacle moves the travel limit.
double World::implicitIncrementLimit() const {
  double limit = implicitLongestIncrement();
  const double travel = implicitTravelLimit();
  for (const SphereObstacle& sphere : state_.spheres) {
    const double speed = sphere.velocity.norm();
    if (speed > 0) limit = std::min(limit, travel / speed);
  }
  return limit;
}

// s, the longest increment that follows a lost equilibrium as dynamics.
double World::implicitDynamicIncrement() const { return settings_.implicit.dynamicIncrementRatio * automaticDt_; }

// m, the farthest an obstacle may move in one increment now.
double World::implicitTravelLimit() const {
  const ImplicitSettings& s = settings_.implicit;
  return state_.implicit.travelFactor * (s.maxTravel > 0 ? s.maxTravel : s.maxTravelRatio * thinnest_);
}

double World::travelPerStep(double speed) const {
  if (settings_.method == SolverMethod::Explicit) return speed * dt_;
  return std::min(implicitTravelLimit(), speed * implicitLongestIncrement());
}

// The residual (and, withMatrix, the tangent) at the bodies' present poses, an increment of dt
// from work.start. Returns the merit sum_i |R_F,i|^2 + |R_T,i / r_i|^2 (r_i: the body's radius).
double World::evaluateIncrement(double dt, bool withMatrix) {
  ImplicitWork& w = *implicit_;
  updatePairs();
  const double band = kCandidateBandRatio * thinnest_;
  const ImplicitScene scene{&state_.bodies, &shapes_, &state_.spheres, &state_.planes, &w.start, parameters_,
                            parameters_.normalStiffness(), parameters_.tangentialStiffness(), dt, band};
  w.results.resize(pairs_.size());
  w.candidates.resize(pairs_.size());
  // The candidates listed this increment stay valid while every pair's sides have moved less than
  // band / sqrt(3) relative to each other since: each side's |dp| + 2 sin(theta / 2) r (the
  // chord of its turn, candidateMotion) at most half of it.
  bool listed = !w.listedPosition.empty();
  for (std::size_t i = 0; i < state_.bodies.size() && listed; ++i)
    listed = (state_.bodies.position[i] - w.listedPosition[i]).norm() +
                 turnChord(state_.bodies.orientation[i], w.listedOrientation[i]) * bodyRadius_[i] <
             0.5 * band / std::sqrt(3.0);
  for (std::size_t k = 0; k < state_.spheres.size() && listed; ++k)
    listed = k < w.listedSphereCentre.size() && (state_.spheres[k].center - w.listedSphereCentre[k]).norm() < 0.5 * band / std::sqrt(3.0);
  if (!listed) {
    for (ImplicitCandidates& c : w.candidates) c.listed = false;
    w.listedPosition = state_.bodies.position;
    w.listedOrientation = state_.bodies.orientation;
    w.listedSphereCentre.clear();
    for (const SphereObstacle& s : state_.spheres) w.listedSphereCentre.push_back(s.center);
  }
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs_.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t p = r.begin(); p != r.end(); ++p) {
        const PairContacts& pair = pairs_[p];
        ImplicitPairResult& result = w.results[p];
        evaluateImplicitPair(scene, pair, committedOf(w.committed, pair), w.candidates[p], result);
        const int b = pair.kind == PairKind::Bodies ? pair.b : pair.a;  // an obstacle pair's: its body's centroid
        if (withMatrix && !result.contacts.empty() && (w.dof[pair.a] >= 0 || w.dof[b] >= 0))
          result.tangent = pairTangent(result, state_.bodies.position[pair.a], state_.bodies.position[b]);
      }
    });
  });

  const RigidBodies& bodies = state_.bodies;
  const std::size_t n = bodies.size();
  w.residual.setZero(6 * w.freeBodies);
  w.bodyScale.assign(n, 0.0);
  w.triplets.clear();
  // The tangent as it is factorised, scaled (ImplicitWork::scale).
  const auto block = [&](int row, int column, const Matrix6& m) {
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        if (m(i, j) != 0) w.triplets.emplace_back(6 * row + i, 6 * column + j, w.scale[6 * row + i] * m(i, j) * w.scale[6 * column + j]);
  };
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const PairContacts& pair = pairs_[p];
    const ImplicitPairResult& r = w.results[p];
    const int a = w.dof[pair.a];
    const bool bodies2 = pair.kind == PairKind::Bodies;
    const int b = bodies2 ? w.dof[pair.b] : -1;
    w.bodyScale[pair.a] += r.forceScale;
    if (a >= 0) w.residual.segment<6>(6 * a) += r.force;
    // Body b: -F at the same points, its generalised force T_b^T (-F_a) (implicit_contacts.h).
    const Eigen::Vector3d cb = bodies2 ? bodies.position[pair.b] : bodies.position[pair.a];
    if (bodies2) {
      w.bodyScale[pair.b] += r.forceScale;
      if (b >= 0) w.residual.segment<6>(6 * b) -= shiftToPoint(bodies.position[pair.a], cb).transpose() * r.force;
    }
    if (!withMatrix || (a < 0 && b < 0)) continue;
    const Eigen::Matrix<double, 12, 12>& K = r.tangent;
    if (a >= 0) block(a, a, K.topLeftCorner<6, 6>());
    if (b >= 0) block(b, b, K.bottomRightCorner<6, 6>());
    if (a >= 0 && b >= 0) {
      block(a, b, K.topRightCorner<6, 6>());
      block(b, a, K.bottomLeftCorner<6, 6>());
    }
  }
  // Gravity and backward Euler's inertia.
  double merit = 0.0;
  w.forceScale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const int d = w.dof[i];
    if (d < 0) continue;
    const double m = bodies.mass[i];
    const Eigen::Vector3d dx = bodies.position[i] - w.startBodies.position[i];
    const Eigen::Vector3d dtheta = rotationBetween(bodies.orientation[i], w.startBodies.orientation[i]);
    const Eigen::Vector3d v0 = w.startBodies.velocity[i], omega0 = w.startBodies.angularVelocity(i);
    const Eigen::Matrix3d& I0 = w.startInertia[i];
    w.residual.segment<3>(6 * d) += m * settings_.gravity - m * (dx / dt - v0) / dt;
    w.residual.segment<3>(6 * d + 3) -= I0 * (dtheta / dt - omega0) / dt;
    if (withMatrix) {
      Matrix6 inertia = Matrix6::Zero();
      inertia.topLeftCorner<3, 3>() = m / (dt * dt) * Eigen::Matrix3d::Identity();
      inertia.bottomRightCorner<3, 3>() = I0 / (dt * dt);
      block(d, d, inertia);
    }
    w.bodyScale[i] += m * settings_.gravity.norm();
    w.forceScale = std::max(w.forceScale, w.bodyScale[i]);
    merit += w.residual.segment<3>(6 * d).squaredNorm() + w.residual.segment<3>(6 * d + 3).squaredNorm() / (bodyRadius_[i] * bodyRadius_[i]);
  }
  if (withMatrix) {
    w.matrix.resize(6 * w.freeBodies, 6 * w.freeBodies);
    w.matrix.setFromTriplets(w.triplets.begin(), w.triplets.end());
  }
  return merit;
}

// Newton's iteration for the increment (the spheres already moved); true when it converged, with
// the bodies at the balanced poses and work.results their contacts.
bool World::solveIncrement(double dt, int& iterations) {
  ImplicitWork& w = *implicit_;
  RigidBodies& bodies = state_.bodies;
  const double tolerance = settings_.implicit.tolerance;
  // The predictor: each free body goes on at its velocity (0 for a body at rest).
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (w.dof[i] < 0) continue;
    bodies.position[i] = w.startBodies.position[i] + dt * w.startBodies.velocity[i];
    bodies.orientation[i] = turned(w.startBodies.orientation[i], dt * w.startBodies.angularVelocity(i));
  }
  double merit = evaluateIncrement(dt, true);
  std::vector<Eigen::Vector3d> position(bodies.size());
  std::vector<Eigen::Quaterniond> orientation(bodies.size());
  for (iterations = 0;; ++iterations) {
    bool converged = w.forceScale == 0 || merit == 0;
    if (!converged) {
      converged = true;
      for (std::size_t i = 0; i < bodies.size() && converged; ++i) {
        const int d = w.dof[i];
        if (d < 0) continue;
        converged = w.residual.segment<3>(6 * d).norm() <= tolerance * w.forceScale &&
                    w.residual.segment<3>(6 * d + 3).norm() <= tolerance * w.forceScale * bodyRadius_[i];
      }
    }
    if (converged) return true;
    if (iterations == settings_.implicit.maxIterations || !std::isfinite(merit)) return false;
    if (w.freeBodies == 0) return true;
    w.solver.analyzePattern(w.matrix);  // natural order (numberFreeBodies'): its elimination tree only
    w.solver.factorize(w.matrix);
    if (w.solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd step = w.scale.cwiseProduct(w.solver.solve(w.scale.cwiseProduct(w.residual)));
    if (w.solver.info() != Eigen::Success || !step.allFinite()) return false;
    // No point moves farther than kStepLimitRatio of the thinnest block in one iteration. A step
    // that moves no point by more than the rounding of its coordinates (64 ulp) ends the
    // iteration: the residual is then at the floor the poses can resolve (a penetration of 1e-10
    // m on a 3 mm coordinate is resolved to 1e-9 of itself).
    double farthest = 0.0;
    bool rounding = true;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (w.dof[i] >= 0) {
        const double moved = step.segment<3>(6 * w.dof[i]).norm() + step.segment<3>(6 * w.dof[i] + 3).norm() * bodyRadius_[i];
        farthest = std::max(farthest, moved);
        rounding = rounding && moved <= 64 * std::numeric_limits<double>::epsilon() * (bodies.position[i].norm() + bodyRadius_[i]);
      }
    if (rounding) return true;
    const double limit = farthest > kStepLimitRatio * thinnest_ ? kStepLimitRatio * thinnest_ / farthest : 1.0;
    position = bodies.position;
    orientation = bodies.orientation;
    // Backtracking: the longest of 1, 1/2, 1/4 of the step that lowers the merit; the
    // shortest if none does (the non-smooth law's active set can need a step up first).
    double length = limit;
    for (int halving = 0; halving <= kLineSearchHalvings; ++halving, length *= 0.5) {
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        const int d = w.dof[i];
        if (d < 0) continue;
        bodies.position[i] = position[i] + length * step.segment<3>(6 * d);
        bodies.orientation[i] = turned(orientation[i], length * step.segment<3>(6 * d + 3));
      }
      const double trial = evaluateIncrement(dt, true);
      if (trial < (1 - 1e-4 * length) * merit || halving == kLineSearchHalvings) {
        merit = trial;
        break;
      }
    }
  }
}

// The converged increment kept: the pairs' contacts and forces, the bodies' backward-Euler
// velocities, the energies, the time.
void World::commitIncrement(double dt, int iterations, bool lost) {
  ImplicitWork& w = *implicit_;
  RigidBodies& bodies = state_.bodies;
  const std::size_t n = bodies.size();
  std::fill(state_.contactForce.begin(), state_.contactForce.end(), Eigen::Vector3d::Zero());
  std::fill(state_.contactTorque.begin(), state_.contactTorque.end(), Eigen::Vector3d::Zero());
  std::fill(state_.sphereReaction.begin(), state_.sphereReaction.end(), Eigen::Vector3d::Zero());
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    PairContacts& pair = pairs_[p];
    ImplicitPairResult& r = w.results[p];
    pair.contacts.assign(r.contacts);
    pair.forceA = r.force.head<3>();
    pair.torqueA = r.force.tail<3>();
    pair.forceB = -pair.forceA;
    pair.torqueB = pair.b >= 0 ? Eigen::Vector3d(-(pair.torqueA + (bodies.position[pair.a] - bodies.position[pair.b]).cross(pair.forceA)))
                               : Eigen::Vector3d::Zero();
    pair.normalForceA = r.normalForceA;
    pair.forcePoint = r.forcePoint;
    pair.tally = r.tally;
    pair.maxDepth = r.maxDepth;
    state_.friction += r.tally.friction;
    state_.damping += r.tally.viscous;
    state_.projection += r.tally.projection;
    state_.contactForce[pair.a] += pair.forceA;
    state_.contactTorque[pair.a] += pair.torqueA;
    if (pair.kind == PairKind::Bodies) {
      state_.contactForce[pair.b] += pair.forceB;
      state_.contactTorque[pair.b] += pair.torqueB;
    } else if (pair.kind == PairKind::Sphere) {
      state_.sphereReaction[-1 - pair.b] += pair.forceB;
    }
  }
  // The obstacles' work over the increment, by the trapezoidal rule on their reactions.
  for (std::size_t k = 0; k < state_.spheres.size(); ++k) {
    const Eigen::Vector3d moved = state_.spheres[k].center - w.start.sphereCentre[k];
    const Eigen::Vector3d before = k < w.startReaction.size() ? w.startReaction[k] : Eigen::Vector3d::Zero();
    state_.externalWork -= 0.5 * (before + state_.sphereReaction[k]).dot(moved);
  }
  // Backward Euler's velocities, and what it dissipates. Its balance m (v - v_0) = dt F_1 (F the
  // contact and gravity forces) gives F_1 . dx = dKE + m |v - v_0|^2 / 2, while the books (the
  // law's energies, the indenter's trapezoidal work) count the forces' work as (F_0 + F_1) . dx / 2:
  // what backward Euler takes out is m |v - v_0|^2 / 2 + (F_0 - F_1) . dx / 2, and the rotation's
  // likewise (for a linear spring K, (F_0 - F_1) . dx = K dx^2: its damping of stiff motions).
  // Where the bodies are in balance at both ends (F_0 = F_1 = 0: quasi-static) it is 0.
  bool dynamic = false;
  for (std::size_t i = 0; i < n; ++i) {
    state_.force[i] = state_.contactForce[i] + bodies.mass[i] * settings_.gravity;
    state_.torque[i] = state_.contactTorque[i];
    state_.dampingForce[i].setZero();
    state_.dampingTorque[i].setZero();
    if (w.dof[i] < 0) continue;
    const Eigen::Vector3d dx = bodies.position[i] - w.startBodies.position[i];
    const Eigen::Vector3d dtheta = rotationBetween(bodies.orientation[i], w.startBodies.orientation[i]);
    const Eigen::Vector3d v = dx / dt, omega = dtheta / dt;
    const Eigen::Vector3d dv = v - w.startBodies.velocity[i], domega = omega - w.startBodies.angularVelocity(i);
    state_.damping += 0.5 * bodies.mass[i] * dv.squaredNorm() + 0.5 * domega.dot(w.startInertia[i] * domega) +
                      0.5 * (w.startForce[i] - state_.force[i]).dot(dx) + 0.5 * (w.startTorque[i] - state_.torque[i]).dot(dtheta);
    dynamic = dynamic || bodies.mass[i] * dv.norm() / dt > 1e-2 * w.forceScale;
    bodies.velocity[i] = v;
    bodies.angularMomentum[i] = bodies.inertia[i].cwiseProduct(bodies.orientation[i].conjugate() * omega);
  }
  ImplicitCounts& counts = state_.implicit;
  counts.iterations += iterations;
  counts.dynamicIncrements += dynamic ? 1 : 0;
  dt_ = dt;
  state_.time += dt;
  ++state_.steps;
  state_.forcesValid = true;
  // An easy increment lets the next double (up to the limit); a hard one keeps its length. One
  // through a lost equilibrium (followed as dynamics) lets the next grow only up to the dynamic
  // increment: past it, while the event goes on, the next would be lost and cut back again.
  counts.increment = iterations <= kEasyIterations ? (lost ? std::max(dt, std::min(2 * dt, implicitDynamicIncrement())) : 2 * dt) : dt;
  // The obstacles' travel limit grows while their reactions change smoothly, and falls back at a jump.
  double change = 0.0, size = 0.0;
  for (std::size_t k = 0; k < state_.spheres.size(); ++k) {
    const Eigen::Vector3d before = k < w.startReaction.size() ? w.startReaction[k] : Eigen::Vector3d::Zero();
    change = std::max(change, (state_.sphereReaction[k] - before).norm());
    size = std::max(size, state_.sphereReaction[k].norm());
  }
  counts.largestReaction = std::max(counts.largestReaction, size);
  const ImplicitSettings& s = settings_.implicit;
  if (change > 4 * s.smoothReactionChange * size) counts.travelFactor = 1.0;
  else if (change <= s.smoothReactionChange * size && iterations <= kEasyIterations && size > 0)
    counts.travelFactor = std::min(2 * counts.travelFactor, s.maxTravelGrowth);
}

// Equilibrium lost over the increment just solved, two ways (each a fall by more than 4 x
// smoothReactionChange of itself over the increment: the balance found at its end lies past a jump):
// - the reaction of an obstacle pressing on the bodies (moving against its reaction: lifting it off
//   unloads them, no event), from at least a tenth of the largest reaction so far (a falling
//   remnant's last touches are no event);
// - a release: the energy stored in the contacts, while an obstacle moves and none unloads, by at
//   least 1 % of the most energy supplied (the slab springing back once the loaded block has left
//   the indenter, which the reaction no longer sees: on a 7 x 7 slab of wave-faced blocks 325 mJ
//   within 1.3 ms, which increments of the indenter's travel took in four and booked with a 30 mJ
//   residual, 3 % of the work).
bool World::lostEquilibrium() const {
  const ImplicitWork& w = *implicit_;
  const double limit = 4 * settings_.implicit.smoothReactionChange;
  bool moving = false, unloading = false;
  for (std::size_t k = 0; k < state_.spheres.size(); ++k) {
    Eigen::Vector3d reaction = Eigen::Vector3d::Zero();
    for (std::size_t p = 0; p < pairs_.size(); ++p)
      if (pairs_[p].kind == PairKind::Sphere && -1 - pairs_[p].b == static_cast<int>(k))
        reaction -= w.results[p].force.head<3>();
    const Eigen::Vector3d& velocity = state_.spheres[k].velocity;
    const Eigen::Vector3d before = k < w.startReaction.size() ? w.startReaction[k] : Eigen::Vector3d::Zero();
    const bool pressing = velocity.dot(before) < 0;  // moving against its reaction: loading, not unloading
    if (pressing && before.norm() >= 0.1 * state_.implicit.largestReaction && reaction.norm() < (1 - limit) * before.norm())
      return true;
    moving = moving || velocity.squaredNorm() > 0;
    unloading = unloading || velocity.dot(before) > 0;
  }
  if (!moving || unloading) return false;
  double storedBefore = 0.0, stored = 0.0;
  for (const PairContacts& pair : w.committed) storedBefore += pair.tally.elastic;
  for (const ImplicitPairResult& r : w.results) stored += r.tally.elastic;
  return storedBefore - stored >= 1e-2 * state_.mostSupplied && stored < (1 - limit) * storedBefore;
}

// Each free body's block of six unknowns (w.dof), numbered in the approximate minimum degree order
// of the graph of the pairs between free bodies (Amestoy, Davis & Duff, SIAM J. Matrix Anal. Appl.
// 17, 1996; Eigen's AMDOrdering). The tangent's blocks lie on that graph's edges (and on a pair's
// found within the increment); factorised in that order, the diagonal pivots kept
// (ImplicitWork::solver), its LU fills in little: on a 31 x 31 slab a factorisation takes 2.4 x
// less time than in COLAMD's column order with partial pivoting.
void World::numberFreeBodies() {
  ImplicitWork& w = *implicit_;
  updatePairs();  // the pairs at the increment's start (the first evaluation finds the same)
  const RigidBodies& bodies = state_.bodies;
  const std::size_t n = bodies.size();
  std::vector<int> freeIndex(n, -1);
  int count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (bodies.moves(i)) freeIndex[i] = count++;
  std::vector<Eigen::Triplet<double>> links;
  for (int k = 0; k < count; ++k) links.emplace_back(k, k, 1.0);
  for (const PairContacts& pair : pairs_)
    if (pair.kind == PairKind::Bodies && freeIndex[pair.a] >= 0 && freeIndex[pair.b] >= 0) {
      links.emplace_back(freeIndex[pair.a], freeIndex[pair.b], 1.0);
      links.emplace_back(freeIndex[pair.b], freeIndex[pair.a], 1.0);
    }
  Eigen::SparseMatrix<double> graph(count, count);
  graph.setFromTriplets(links.begin(), links.end());
  std::vector<int> position(count);
  if (count > 0) {
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;  // order.indices()[k]: the k-th eliminated
    Eigen::AMDOrdering<int>()(graph, order);
    for (int k = 0; k < count; ++k) position[order.indices()[k]] = k;
  }
  w.dof.assign(n, -1);
  w.freeBodies = count;
  w.scale.resize(6 * count);
  for (std::size_t i = 0; i < n; ++i) {
    if (freeIndex[i] < 0) continue;
    const int d = w.dof[i] = position[freeIndex[i]];
    w.scale.segment<3>(6 * d).setOnes();
    w.scale.segment<3>(6 * d + 3).setConstant(1.0 / bodyRadius_[i]);
  }
}

void World::implicitStep() {
  if (!implicit_) implicit_ = std::make_unique<ImplicitWork>();
  ImplicitWork& w = *implicit_;
  RigidBodies& bodies = state_.bodies;
  const std::size_t n = bodies.size();
  numberFreeBodies();
  w.startBodies = bodies;
  w.start.position = bodies.position;
  w.start.orientation = bodies.orientation;
  w.start.sphereCentre.clear();
  for (const SphereObstacle& s : state_.spheres) w.start.sphereCentre.push_back(s.center);
  w.startReaction = state_.sphereReaction;
  w.startInertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Matrix3d R = bodies.orientation[i].toRotationMatrix();
    w.startInertia[i] = R * bodies.inertia[i].asDiagonal() * R.transpose();
  }
  w.committed = pairs_;
  std::sort(w.committed.begin(), w.committed.end(), pairsByBodies);
  if (state_.steps == 0) {
    // The energy stored at the start (an assembly built overlapping), and the forces there: the
    // residual of an increment too long for inertia to count, with no motion.
    evaluateIncrement(1e150, false);
    double elastic = 0.0;
    for (const ImplicitPairResult& r : w.results) elastic += r.tally.elastic;
    state_.initialEnergy = elastic;
    for (std::size_t i = 0; i < n; ++i) {
      if (!bodies.moves(i)) continue;
      state_.initialEnergy += bodies.kineticEnergy(i);
      state_.force[i] = w.residual.segment<3>(6 * w.dof[i]);
      state_.torque[i] = w.residual.segment<3>(6 * w.dof[i] + 3);
    }
  }
  w.startForce = state_.force;
  w.startTorque = state_.torque;

  const double limit = implicitIncrementLimit();
  // The first increment is short (kFirstIncrementRatio explicit steps: inertia holds Newton's
  // first steps while contacts close); each easy one doubles the next.
  const double first = std::min(limit, kFirstIncrementRatio * automaticDt_);
  double dt = std::min(state_.implicit.increment > 0 ? state_.implicit.increment : first, limit);
  int iterations = 0;
  bool lost = false;
  for (;;) {
    for (std::size_t k = 0; k < state_.spheres.size(); ++k)
      state_.spheres[k].center = w.start.sphereCentre[k] + dt * state_.spheres[k].velocity;
    int tried = 0;
    const bool converged = solveIncrement(dt, tried);
    iterations += tried;
    lost = converged && lostEquilibrium();
    if (converged && !(lost && dt > implicitDynamicIncrement())) break;
    // Cut: back to the start, a quarter of the increment.
    bodies = w.startBodies;
    pairs_ = w.committed;
    state_.pairsValid = false;
    ++state_.implicit.cutbacks;
    dt *= 0.25;
    if (dt < 1e-12 * limit)
      throw SolverInstability(format("t = %.6g s: no balance of forces found even over an increment of %.3g s; ", state_.time, dt) +
                              "the assembly or the loading is beyond what the implicit method can follow; try "
                              "solver.method = \"explicit\"");
  }
  commitIncrement(dt, iterations, lost);
  checkStability();
}

}  // namespace tessera

#include "levelset/elastic_settling.h"

#include "levelset/rigid_block_freedoms.h"

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

using rigid_blocks::Freedoms;

namespace {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

// The springs of the contact nodes and the weights, in the columns of Freedoms (lengths in units of
// L, stiffness per L^2 of area, weights as volumes / L^3: density, g and the stiffness's scale
// factored out). A spring's rows act on its pair's 12 columns: the first body's (v, L w), then the
// second's (zero for a fixed body).
class NodeSprings {
public:
  NodeSprings(const Bundle& bundle, const Freedoms& freedoms, const std::vector<ContactNode>& nodes)
      : columns_(6 * freedoms.count), weight_(rigid_blocks::weights(bundle, freedoms)) {
    for (const ContactNode& node : nodes) {
      if (pairs_.empty() || pairs_.back().first != node.first || pairs_.back().second != node.second)
        pairs_.push_back({node.first, node.second, freedoms.index[node.first], freedoms.index[node.second], springs_.size(), springs_.size()});
      const Eigen::Vector3d& n = node.normal;
      const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
      Spring spring;
      spring.stiffness = node.area / std::pow(freedoms.length, 2);
      const Eigen::Vector3d direction[3] = {n, u, v};
      for (int k = 0; k < 3; ++k) {  // n . (u_second(p) - u_first(p)): + on the second, - on the first
        Vector12& row = k == 0 ? spring.normal : spring.tangent[k - 1];
        const Eigen::Vector3d armFirst = (node.point - freedoms.position[node.first]).cross(direction[k]) / freedoms.length;
        const Eigen::Vector3d armSecond = (node.point - freedoms.position[node.second]).cross(direction[k]) / freedoms.length;
        row << -direction[k], -armFirst, direction[k], armSecond;
      }
      springs_.push_back(spring);
      pairs_.back().end = springs_.size();
    }
    displacementScale_ = ownWeightDisplacement();
  }

  int columns() const { return columns_; }
  double totalWeight() const { return weight_.sum(); }

  /// Every spring's cap on its tangential force at x: Coulomb's mu f_n, f_n = k max(0, -n.x), so
  /// none where the spring is open; mu < 0: no cap (every tangential spring sticks, open or not:
  /// a convex problem, the start of the others).
  Eigen::VectorXd caps(const Eigen::VectorXd& x, double mu) const {
    Eigen::VectorXd c(springs_.size());
    for (const Pair& pair : pairs_) {
      const Vector12 local = gather(pair, x);
      for (std::size_t i = pair.begin; i < pair.end; ++i)
        c[i] = mu < 0 ? std::numeric_limits<double>::infinity() : mu * springs_[i].stiffness * std::max(0.0, -springs_[i].normal.dot(local));
    }
    return c;
  }

  /// With the tangential caps c held (Tresca's law), the springs store a convex energy
  ///   Phi(x) = sum_i k/2 min(0, g)^2 + psi(|s|) + W.x,   g = n.x, s = T x,
  ///   psi(r) = k r^2 / 2 (r <= c / k: sticking),  c r - c^2 / (2k) (beyond: slipping at the cap),
  /// continuously differentiable, its gradient the out-of-balance force with the sign turned,
  /// -R(x) = W - sum (f_n n + T^T f_t). Returns Phi, and, if asked for, the gradient, the
  /// Hessian (triplets; at g = 0 the normal spring counts as closed, so the first step from x = 0
  /// sees every contact) and the sum of the normal forces. `coulomb` = mu > 0: the caps passed are
  /// Coulomb's, mu f_n(x), and the matrix is the gradient's Jacobian with their change (not
  /// symmetric), for solving Coulomb's law itself.
  double energy(const Eigen::VectorXd& x, const Eigen::VectorXd& caps, Eigen::VectorXd* gradient,
                std::vector<Eigen::Triplet<double>>* hessian, double* normalSum, double coulomb = -1) const {
    double phi = weight_.dot(x);  // the weights' potential: W is the lift that holds them
    if (gradient) *gradient = weight_;
    if (hessian) hessian->clear();
    if (normalSum) *normalSum = 0;
    for (const Pair& pair : pairs_) {
      const Vector12 local = gather(pair, x);
      Vector12 slope = Vector12::Zero();
      Matrix12 curvature = Matrix12::Zero();
      for (std::size_t i = pair.begin; i < pair.end; ++i) {
        const Spring& s = springs_[i];
        const double k = s.stiffness, gap = s.normal.dot(local), cap = caps[i];
        if (gap <= 0) {
          phi += 0.5 * k * gap * gap;
          slope += k * gap * s.normal;
          if (hessian) curvature.noalias() += k * s.normal * s.normal.transpose();
          if (normalSum) *normalSum -= k * gap;
        }
        if (cap <= 0) continue;
        const Eigen::Vector2d slide(s.tangent[0].dot(local), s.tangent[1].dot(local));
        const double length = slide.norm();
        if (k * length <= cap) {  // sticking: a linear spring
          phi += 0.5 * k * length * length;
          slope += k * (slide[0] * s.tangent[0] + slide[1] * s.tangent[1]);
          if (hessian) curvature.noalias() += k * (s.tangent[0] * s.tangent[0].transpose() + s.tangent[1] * s.tangent[1].transpose());
          continue;
        }
        // Slipping: the force c s^ along the slide; its derivative (c / |s|) (I - s^ s^T) across it.
        const Eigen::Vector2d along = slide / length;
        phi += cap * length - 0.5 * cap * cap / k;
        slope += cap * (along[0] * s.tangent[0] + along[1] * s.tangent[1]);
        if (!hessian) continue;
        const Vector12 across = -along[1] * s.tangent[0] + along[0] * s.tangent[1];
        curvature.noalias() += cap / length * across * across.transpose();
        if (coulomb > 0)  // the cap's own change, c = mu k (-g) > 0 (so g < 0): not symmetric
          curvature.noalias() -= coulomb * k * (along[0] * s.tangent[0] + along[1] * s.tangent[1]) * s.normal.transpose();
      }
      if (gradient) scatter(pair, slope, *gradient);
      if (hessian) scatterMatrix(pair, curvature, *hessian);
    }
    return phi;
  }

  /// The displacement of a body under its own weight on its own springs, the largest: the scale
  /// against which a motion that grows without bound is told (a fall).
  double displacementScale() const { return displacementScale_; }

private:
  double ownWeightDisplacement() const {
    Eigen::VectorXd held = Eigen::VectorXd::Zero(weight_.size());
    for (const Pair& pair : pairs_)
      for (std::size_t i = pair.begin; i < pair.end; ++i) {
        if (pair.freeFirst >= 0) held[6 * pair.freeFirst] += springs_[i].stiffness;
        if (pair.freeSecond >= 0) held[6 * pair.freeSecond] += springs_[i].stiffness;
      }
    double scale = 0;
    for (int b = 0; b < weight_.size(); b += 6) {
      const double w = weight_.segment<6>(b).norm();
      if (held[b] > 0) scale = std::max(scale, w / held[b]);
    }
    return scale > 0 ? scale : 1.0;
  }

  struct Spring {  // one node: its rows along the normal (positive: opening) and two tangents
    Vector12 normal, tangent[2];
    double stiffness = 0;
  };
  struct Pair {
    int first, second, freeFirst, freeSecond;  // bodies and their ranks among the free ones (-1: fixed)
    std::size_t begin, end;                   // its springs
  };
  static Vector12 gather(const Pair& pair, const Eigen::VectorXd& x) {
    Vector12 local = Vector12::Zero();
    if (pair.freeFirst >= 0) local.head<6>() = x.segment<6>(6 * pair.freeFirst);
    if (pair.freeSecond >= 0) local.tail<6>() = x.segment<6>(6 * pair.freeSecond);
    return local;
  }
  static void scatter(const Pair& pair, const Vector12& local, Eigen::VectorXd& r) {
    if (pair.freeFirst >= 0) r.segment<6>(6 * pair.freeFirst) += local.head<6>();
    if (pair.freeSecond >= 0) r.segment<6>(6 * pair.freeSecond) += local.tail<6>();
  }
  static void scatterMatrix(const Pair& pair, const Matrix12& local, std::vector<Eigen::Triplet<double>>& jacobian) {
    const int rank[2] = {pair.freeFirst, pair.freeSecond};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        if (rank[a] >= 0 && rank[b] >= 0)
          for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j) jacobian.emplace_back(6 * rank[a] + i, 6 * rank[b] + j, local(6 * a + i, 6 * b + j));
  }

  int columns_;
  Eigen::VectorXd weight_;
  std::vector<Spring> springs_;
  std::vector<Pair> pairs_;
  double displacementScale_ = 1.0;
};

// Every solver below stops when each component of the out-of-balance force is within kTolerance
// of the weight plus the normal forces.
constexpr double kTolerance = 1e-9;

enum class Outcome { stands, falls, stalled };

// Phi's minimum with the caps held, by Newton's method on the convex energy with a backtracking
// (Armijo) line search (J. Nocedal & S. J. Wright, "Numerical Optimization", 2nd ed., 2006, ch. 3):
// each step solves (H + delta I) d = -grad Phi, delta = 1e-12 of H's largest diagonal (a motion no
// spring holds gets a long step, not a singular matrix). Unbounded (falls) when x grows past 1e6
// times the displacement scale: the energy falls without end, the weights doing more work along a
// motion than its springs can store or the held caps dissipate; at once when no spring holds
// anything. Stalled after budget.newtonSteps.

Outcome minimise(const NodeSprings& springs, const SettlingBudget& budget, const Eigen::VectorXd& caps, Eigen::VectorXd& x) {
  const double bound = 1e6 * springs.displacementScale();
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  Eigen::VectorXd gradient;
  for (int step = 0; step < budget.newtonSteps; ++step) {
    double normalSum = 0;
    const double phi = springs.energy(x, caps, &gradient, &triplets, &normalSum);
    if (gradient.cwiseAbs().maxCoeff() <= kTolerance * (springs.totalWeight() + normalSum)) return Outcome::stands;
    Eigen::SparseMatrix<double> h(springs.columns(), springs.columns());
    h.setFromTriplets(triplets.begin(), triplets.end());
    if (!(h.diagonal().maxCoeff() > 0)) {  // nothing holds the bodies: they go the weights' way
      x -= 2 * bound / gradient.cwiseAbs().maxCoeff() * gradient;
      return Outcome::falls;
    }
    const double delta = 1e-12 * h.diagonal().maxCoeff();
    for (int i = 0; i < springs.columns(); ++i) h.coeffRef(i, i) += delta;
    solver.compute(h);
    if (solver.info() != Eigen::Success) return Outcome::stalled;
    const Eigen::VectorXd d = -solver.solve(gradient);
    const double descent = gradient.dot(d), rounding = 1e-13 * std::abs(phi);  // below it, energies tie
    double t = 1;
    while (springs.energy(x + t * d, caps, nullptr, nullptr, nullptr) > phi + 1e-4 * t * descent + rounding)
      if ((t *= 0.5) < 1e-12) return Outcome::stalled;
    x += t * d;
    if (x.cwiseAbs().maxCoeff() > bound) return Outcome::falls;
  }
  return Outcome::stalled;
}

// Coulomb's law itself, R(x) = 0 with the caps mu f_n(x), by pseudo-transient continuation (C. T.
// Kelley & D. E. Keyes, "Convergence analysis of pseudo-transient continuation", SIAM J. Numer.
// Anal. 35, 1998): steps (J + I / dt) dx = -grad, J the Jacobian of the out-of-balance force with
// the sign turned (not symmetric: the caps move with x), Newton's for long pseudo-times dt and a
// damped relaxation for short ones, which moves a body that no spring holds by a bounded amount.
// 1/dt starts at `shift` times J's largest diagonal and follows |grad| (switched evolution
// relaxation): it shrinks with |grad| (at least halving), grows fourfold the ratio when |grad|
// rises by more than 5 % (a node chattering between sticking and slipping, or open and closed, is
// damped onto the kink), and shrinks fourfold when |grad| stays (a damped step stuck at a kink is
// freed); a step that raises |grad| tenfold is taken back with 1/dt ten times larger. False after
// budget.relaxSteps steps, or budget.stall steps without halving |grad|.
bool relax(const NodeSprings& springs, const SettlingBudget& budget, double mu, double shift, Eigen::VectorXd& x) {
  std::vector<Eigen::Triplet<double>> triplets, nextTriplets;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
  Eigen::VectorXd gradient, next;
  double normalSum = 0, best = 1e300;
  int improved = 0;  // the step at which |grad| last fell below half its best
  springs.energy(x, springs.caps(x, mu), &gradient, &triplets, &normalSum, mu);
  for (int step = 0; step < budget.relaxSteps && step - improved <= budget.stall; ++step) {
    const double norm = gradient.norm();
    if (norm < 0.5 * best) best = norm, improved = step;
    if (gradient.cwiseAbs().maxCoeff() <= kTolerance * (springs.totalWeight() + normalSum)) return true;
    Eigen::SparseMatrix<double> j(springs.columns(), springs.columns());
    j.setFromTriplets(triplets.begin(), triplets.end());
    const double largest = std::max(j.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    if (step == 0) shift *= largest;
    shift = std::max(shift, 1e-10 * largest);
    for (int i = 0; i < springs.columns(); ++i) j.coeffRef(i, i) += shift;
    j.makeCompressed();
    solver.compute(j);
    if (solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd trial = x - solver.solve(gradient);
    double nextNormal = 0;
    springs.energy(trial, springs.caps(trial, mu), &next, &nextTriplets, &nextNormal, mu);
    if (!(next.norm() < 10 * norm)) {  // taken back
      shift *= 10;
      continue;
    }
    const double ratio = next.norm() / norm;
    shift *= ratio < 1 ? std::min(0.5, ratio) : ratio > 1.05 ? 4 * ratio : 0.25;
    x = trial;
    std::swap(gradient, next);
    std::swap(triplets, nextTriplets);
    normalSum = nextNormal;
  }
  return false;
}

// Coulomb's law as a fixed point of Tresca's (P. D. Panagiotopoulos, "A nonlinear programming
// approach to the unilateral contact- and friction-boundary value problem", Ing.-Arch. 44, 1975):
// the caps mu f_n taken from x, Phi minimised with them held (a convex problem: its minimum is
// found or shown unbounded), again, for budget.rounds or until the out-of-balance force with the
// minimum's own caps is within kNear of the loads; then relaxed to the tolerance from the closest
// round (near a kink the rounds cycle). Falls when the first round's minimum is unbounded.
constexpr double kNear = 1e-3;

Outcome tresca(const NodeSprings& springs, const SettlingBudget& budget, double mu, Eigen::VectorXd& x) {
  Eigen::VectorXd caps = springs.caps(x, mu), gradient, closest = x;
  double closestResidual = 1e300;
  for (int round = 0; round < budget.rounds; ++round) {
    const Outcome minimum = minimise(springs, budget, caps, x);
    // A fall is taken only with the caps of the state it started from (an equilibrium: the last
    // friction's, or every spring sticking): later rounds' caps are no state of the bodies.
    if (minimum == Outcome::falls && round > 0) return Outcome::stalled;
    if (minimum != Outcome::stands) return minimum;
    caps = springs.caps(x, mu);
    double normalSum = 0;
    springs.energy(x, caps, &gradient, nullptr, &normalSum);
    const double residual = gradient.cwiseAbs().maxCoeff();
    if (residual < closestResidual) closestResidual = residual, closest = x;
    if (residual <= kNear * (springs.totalWeight() + normalSum)) break;
  }
  x = closest;
  return relax(springs, budget, mu, 1e-6, x) ? Outcome::stands : Outcome::stalled;
}

// R(x) = 0 at friction mu from the equilibrium x of a neighbouring friction: first relaxed from
// there, damped (the solution that the bodies, slowly let go, would settle into); failing that,
// by Tresca's fixed point, which also tells a fall. x: the solution, or the last attempt.
Outcome equilibrium(const NodeSprings& springs, const SettlingBudget& budget, double mu, Eigen::VectorXd& x) {
  Eigen::VectorXd y = x;
  if (relax(springs, budget, mu, 1e-2, y)) {
    x = y;
    return Outcome::stands;
  }
  return tresca(springs, budget, mu, x);
}

}  // namespace

ElasticSettling settleElastically(const Bundle& bundle, const std::vector<ContactNode>& nodes, double friction, bool findLeastFriction,
                                  const SettlingBudget& budget) {
  const Freedoms freedoms(bundle);
  ElasticSettling result;
  result.stands = true;
  result.leastFriction = 0;
  if (freedoms.count == 0) return result;
  const NodeSprings springs(bundle, freedoms, nodes);
  // From every tangential spring sticking (a convex start), without friction straight from there:
  // an assembly that stands so needs no path (a convex problem's minimum). Else from friction 10
  // (or the one asked for, if higher) down: each friction's solution starts from the last one's,
  // the step shrinking where the solution fails, until the last failed step is within 2 % (there
  // the branch ends: with less friction the bodies fall) or 0 is reached; unless the least is
  // searched, the same steps stop once the friction asked for is passed, so that both give one
  // verdict.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(springs.columns()), y = x;
  const Outcome sticking = minimise(springs, budget, springs.caps(x, -1), y);  // every tangential spring sticking
  if (sticking != Outcome::stands) {  // unbounded: a body no contact holds; stalled: undecided
    result.stands = false;
    result.leastFriction.reset();
    result.decided = sticking == Outcome::falls;
    result.falling = rigid_blocks::motionOf(freedoms, y);
    return result;
  }
  x = y;
  Eigen::VectorXd frictionless = x;
  if (minimise(springs, budget, springs.caps(x, 0), frictionless) == Outcome::stands) return result;  // least friction 0
  const double start = std::max(rigid_blocks::kMostFriction, friction);
  double mu = start, factor = 0.5;
  y = x;
  const Outcome first = equilibrium(springs, budget, mu, y);
  result.decided = first != Outcome::stalled;
  bool going = first == Outcome::stands;  // false: the branch has ended (at mu)
  const bool startsStanding = going;
  while (going && mu > 0 && (findLeastFriction || mu > friction)) {
    x = y;
    const double next = mu * factor < 1e-3 ? 0.0 : mu * factor;
    if (equilibrium(springs, budget, next, y) == Outcome::stands) {
      mu = next;
      factor = std::max(0.5, factor * factor);
    } else if ((factor = std::sqrt(factor)) > 0.99) {
      going = false;
    } else {
      y = x;
    }
  }
  result.stands = startsStanding && mu <= friction;
  if (!startsStanding) result.leastFriction.reset();                // not even at the start
  else if (findLeastFriction || !going) result.leastFriction = mu;  // where the branch ended (or 0)
  else result.leastFriction.reset();                                // stands at `friction`; the least not looked for
  if (!result.stands) result.falling = rigid_blocks::motionOf(freedoms, y - x);  // the last attempt's way down
  return result;
}

}  // namespace tessera

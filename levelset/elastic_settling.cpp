#include "levelset/elastic_settling.h"

#include "levelset/rigid_block_freedoms.h"

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>

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
  }

  int columns() const { return columns_; }
  double totalWeight() const { return weight_.sum(); }

  /// The out-of-balance force R = sum (f_n n + T^T f_t) - W at x and friction mu, and its
  /// Jacobian dR/dx as triplets (if asked for); the sum of the normal forces in `normalSum`.
  /// Normal: f_n = k max(0, -n.x) (a closed spring at zero gap counts as loaded, so that the first
  /// step from x = 0 sees every contact). Tangential: f_t = -k s (s = T x, sticking) or
  /// -mu f_n s/|s| (slipping, when k |s| > mu f_n); none where the spring is open. mu < 0: every
  /// tangential spring sticks, open or not (a convex problem, the start of the others).
  Eigen::VectorXd residual(const Eigen::VectorXd& x, double mu, std::vector<Eigen::Triplet<double>>* jacobian, double* normalSum = nullptr) const {
    Eigen::VectorXd r = -weight_;
    if (jacobian) jacobian->clear();
    if (normalSum) *normalSum = 0;
    for (const Pair& pair : pairs_) {
      const Vector12 local = gather(pair, x);
      Vector12 force = Vector12::Zero();
      Matrix12 stiffness = Matrix12::Zero();
      for (std::size_t c = pair.begin; c < pair.end; ++c) {
        const Spring& s = springs_[c];
        const double k = s.stiffness, gap = s.normal.dot(local);
        if (gap > 0 && mu >= 0) continue;  // open: no force
        const double normal = gap > 0 ? 0.0 : -k * gap;
        if (normalSum) *normalSum += normal;
        force += normal * s.normal;
        if (jacobian && gap <= 0) stiffness.noalias() -= k * s.normal * s.normal.transpose();
        const Eigen::Vector2d slide(s.tangent[0].dot(local), s.tangent[1].dot(local));
        const double length = slide.norm();
        if (mu < 0 || k * length <= mu * normal) {  // sticking: a linear spring
          force -= k * (slide[0] * s.tangent[0] + slide[1] * s.tangent[1]);
          if (jacobian) stiffness.noalias() -= k * (s.tangent[0] * s.tangent[0].transpose() + s.tangent[1] * s.tangent[1].transpose());
          continue;
        }
        // Slipping: f_t = -mu k p s^ with p = -gap; df_t/dx = mu k s^ n^T - (mu f_n / |s|) (I - s^ s^T) T.
        const Eigen::Vector2d along = slide / length;
        const Vector12 slideRow = along[0] * s.tangent[0] + along[1] * s.tangent[1];
        force -= mu * normal * slideRow;
        if (!jacobian) continue;
        stiffness.noalias() += mu * k * slideRow * s.normal.transpose();
        const Vector12 across = -along[1] * s.tangent[0] + along[0] * s.tangent[1];
        stiffness.noalias() -= mu * normal / length * across * across.transpose();
      }
      scatter(pair, force, r);
      if (jacobian) scatterMatrix(pair, stiffness, *jacobian);
    }
    return r;
  }

private:
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
};

// R(x) = 0 at friction mu, from x, by pseudo-transient continuation (C. T. Kelley & D. E. Keyes,
// "Convergence analysis of pseudo-transient continuation", SIAM J. Numer. Anal. 35, 1998): steps
// (-J + I / dt) dx = R, Newton's for long pseudo-times dt and a damped relaxation for short ones,
// which moves a body that no spring holds by a bounded amount. 1/dt starts at 1e-2 of the
// largest stiffness and follows |R| (switched evolution relaxation): it shrinks with |R| (at least
// halving), grows fourfold the ratio when |R| rises by more than 5 % (a node chattering between
// sticking and slipping, or open and closed, is damped onto the kink), and shrinks fourfold when
// |R| stays (a damped step stuck at a kink is freed); a step that raises |R| tenfold is taken back
// with 1/dt ten times larger. True when every component of R is below 1e-9 of the weight plus the
// normal forces; false after kMostSteps steps, or kStall steps without halving |R|. (At 80 and 15
// the friction at which the 7 x 7 triangle slabs' branches ended was 15-370 % higher, and the
// 15 x 15 square slab's at 4.4 instead of 0.066, with the old rule for a stalled |R|.)
constexpr int kMostSteps = 400;
constexpr int kStall = 60;

bool equilibrium(const NodeSprings& springs, double mu, Eigen::VectorXd& x) {
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
  double normalSum = 0, shift = -1, best = 1e300;
  int improved = 0;  // the step at which |R| last fell below half its best
  Eigen::VectorXd r = springs.residual(x, mu, &triplets, &normalSum);
  for (int iteration = 0; iteration < kMostSteps && iteration - improved <= kStall; ++iteration) {
    const double norm = r.norm();
    if (norm < 0.5 * best) best = norm, improved = iteration;
    if (r.cwiseAbs().maxCoeff() <= 1e-9 * (springs.totalWeight() + normalSum)) return true;
    Eigen::SparseMatrix<double> j(springs.columns(), springs.columns());
    j.setFromTriplets(triplets.begin(), triplets.end());
    j = -j;
    const double largest = std::max(j.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    if (shift < 0) shift = 1e-2 * largest;
    shift = std::max(shift, 1e-10 * largest);
    for (int i = 0; i < springs.columns(); ++i) j.coeffRef(i, i) += shift;
    j.makeCompressed();
    solver.compute(j);
    if (solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd trial = x + solver.solve(r);
    std::vector<Eigen::Triplet<double>> nextTriplets;
    double nextNormal = 0;
    Eigen::VectorXd next = springs.residual(trial, mu, &nextTriplets, &nextNormal);
    if (!(next.norm() < 10 * norm)) {  // taken back
      shift *= 10;
      continue;
    }
    const double ratio = next.norm() / norm;
    shift *= ratio < 1 ? std::min(0.5, ratio) : ratio > 1.05 ? 4 * ratio : 0.25;
    x = trial;
    r = std::move(next);
    triplets = std::move(nextTriplets);
    normalSum = nextNormal;
  }
  return false;
}

}  // namespace

ElasticSettling settleElastically(const Bundle& bundle, const std::vector<ContactNode>& nodes, double friction, bool findLeastFriction) {
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
  if (equilibrium(springs, -1, y)) x = y;  // every tangential spring sticking
  Eigen::VectorXd frictionless = x;
  if (equilibrium(springs, 0, frictionless)) return result;  // stands, least friction 0
  const double start = std::max(rigid_blocks::kMostFriction, friction);
  double mu = start, factor = 0.5;
  y = x;
  bool going = equilibrium(springs, mu, y);  // false: the branch has ended (at mu)
  const bool startsStanding = going;
  while (going && mu > 0 && (findLeastFriction || mu > friction)) {
    x = y;
    const double next = mu * factor < 1e-3 ? 0.0 : mu * factor;
    if (equilibrium(springs, next, y)) {
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

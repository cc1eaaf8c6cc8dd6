#include "levelset/rigid_block_analysis.h"

#include "levelset/elastic_settling.h"
#include "levelset/rigid_block_freedoms.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <glpk.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace tessera {

using rigid_blocks::Entry;
using rigid_blocks::Freedoms;
using rigid_blocks::motionOf;
using rigid_blocks::wrench;

namespace {

// A GLPK problem, deleted with it.
struct LinearProgram {
  std::unique_ptr<glp_prob, void (*)(glp_prob*)> lp{glp_create_prob(), glp_delete_prob};
  glp_prob* get() const { return lp.get(); }

  // Loads the (row, column, value) triplets, 0-based.
  void load(const std::vector<int>& rows, const std::vector<int>& columns, const std::vector<double>& values) {
    std::vector<int> ia{0}, ja{0};
    std::vector<double> ar{0};
    for (std::size_t i = 0; i < rows.size(); ++i) {
      ia.push_back(rows[i] + 1);
      ja.push_back(columns[i] + 1);
      ar.push_back(values[i]);
    }
    glp_load_matrix(get(), static_cast<int>(rows.size()), ia.data(), ja.data(), ar.data());
  }

  bool interior = false;  // the last solve was the interior-point method's
  double primal(int column) const { return interior ? glp_ipt_col_prim(get(), column) : glp_get_col_prim(get(), column); }

  // The interior-point method (glp_interior: a primal-dual path-following method on the normal
  // equations, sparse Cholesky), for the equilibrium programs: any feasible point will do, and on
  // a 15 x 15 slab (3 198 rows, 19 656 columns) it took 0.3-0.4 s where the dual simplex took
  // 7 s. Its feasible point is a certificate (checked to 1e-12 of the weights on a triangle slab);
  // its "infeasible" is not (GLPK's detection is a heuristic: the merit growing 10^5-fold), so that
  // answer, numerical trouble and an undecided status are left to the simplex method.
  bool solveInterior() {
    glp_term_out(GLP_OFF);
    glp_iptcp parameters;
    glp_init_iptcp(&parameters);
    parameters.msg_lev = GLP_MSG_OFF;
    const int code = glp_interior(get(), &parameters);
    interior = true;
    if (code == 0 && glp_ipt_status(get()) == GLP_OPT) return true;
    return solve();
  }

  // True when the simplex method finds an optimum; false when the problem has no feasible point.
  bool solve() {
    interior = false;
    glp_term_out(GLP_OFF);
    glp_smcp parameters;
    glp_init_smcp(&parameters);
    parameters.msg_lev = GLP_MSG_OFF;
    parameters.meth = GLP_DUALP;  // the dual simplex, falling back to the primal: steadier on these degenerate programs
    // The long-step ratio test (bound flipping) of the dual simplex: on a 31 x 31 slab's motion
    // programs (10 440 rows, 5 046 columns, degenerate at x = 0) 47 -> 18 s and over 60 -> 36 s.
    parameters.r_test = GLP_RT_FLIP;
    parameters.presolve = GLP_ON;
    int code = glp_simplex(get(), &parameters);
    if (code == GLP_EBADB || code == GLP_ESING || code == GLP_ECOND) {  // the old basis no longer serves
      glp_adv_basis(get(), 0);
      code = glp_simplex(get(), &parameters);
    }
    if (code == GLP_ENOPFS || code == GLP_ENODFS) return false;
    if (code != 0) throw std::runtime_error("the linear program could not be solved (GLPK code " + std::to_string(code) + ")");
    return glp_get_status(get()) == GLP_OPT;
  }
};

// The motions with A x = 0 (sliding along every contact): their number, from the eigenvalues of
// A^T A below 1e-12 of the largest (singular values below 1e-6), and one of them.
struct SlidingModes {
  int count = 0;
  Eigen::VectorXd example;
};
SlidingModes slidingModes(const Eigen::SparseMatrix<double>& a) {
  SlidingModes modes;
  const Eigen::SparseMatrix<double> normal = a.transpose() * a;
  if (normal.rows() <= 3600) {  // 600 free bodies: dense
    const Eigen::MatrixXd dense(normal);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(dense);
    const double largest = std::max(eigen.eigenvalues().maxCoeff(), 1e-300);
    while (modes.count < eigen.eigenvalues().size() && eigen.eigenvalues()(modes.count) <= 1e-12 * largest) ++modes.count;
    if (modes.count > 0) modes.example = eigen.eigenvectors().col(0);
    return modes;
  }
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);  // pivots of a singular matrix vanish
  const Eigen::VectorXd d = ldlt.vectorD().cwiseAbs();
  for (int i = 0; i < d.size(); ++i) modes.count += d[i] <= 1e-12 * d.maxCoeff();
  return modes;
}

// A: row c the corner's relative normal velocity (A x)_c, as triplets.
std::vector<Eigen::Triplet<double>> contactMatrix(const Freedoms& freedoms, const std::vector<ContactCorner>& corners) {
  std::vector<Eigen::Triplet<double>> triplets;
  for (int c = 0; c < static_cast<int>(corners.size()); ++c)
    for (const Entry& e : wrench(freedoms, corners[c], corners[c].normal)) triplets.emplace_back(c, e.column, e.value);
  return triplets;
}

// The motion that opens the contacts most: max sum_c s_c, s = A x, 0 <= s <= 1, |x| <= 1 (always
// feasible, x = 0, and bounded); an optimum above kOpen is a way out. Returns x and the optimum.
constexpr double kOpen = 1e-6;
std::pair<Eigen::VectorXd, double> mostOpening(const std::vector<Eigen::Triplet<double>>& triplets, int rows, int columns) {
  LinearProgram lp;
  glp_set_obj_dir(lp.get(), GLP_MAX);
  if (rows > 0) glp_add_rows(lp.get(), rows);
  for (int c = 1; c <= rows; ++c) glp_set_row_bnds(lp.get(), c, GLP_DB, 0, 1);
  Eigen::VectorXd objective = Eigen::VectorXd::Zero(columns);  // sum_c (A x)_c
  for (const auto& t : triplets) objective[t.col()] += t.value();
  glp_add_cols(lp.get(), columns);
  for (int d = 1; d <= columns; ++d) {
    glp_set_col_bnds(lp.get(), d, GLP_DB, -1, 1);
    glp_set_obj_coef(lp.get(), d, objective[d - 1]);
  }
  std::vector<int> ri, ci;
  std::vector<double> vi;
  for (const auto& t : triplets) {
    ri.push_back(t.row());
    ci.push_back(t.col());
    vi.push_back(t.value());
  }
  lp.load(ri, ci, vi);
  if (!lp.solve()) throw std::runtime_error("a motion program has no solution, yet x = 0 solves it");
  Eigen::VectorXd x(columns);
  for (int d = 0; d < columns; ++d) x[d] = glp_get_col_prim(lp.get(), d + 1);
  return {x, glp_get_obj_val(lp.get())};
}

// The free bodies that touch nothing: each moves freely (lifted off, say).
std::vector<int> looseBodies(const Freedoms& freedoms, const std::vector<ContactCorner>& corners) {
  std::vector<char> touches(freedoms.index.size(), 0);
  for (const ContactCorner& c : corners) touches[c.first] = touches[c.second] = 1;
  std::vector<int> loose;
  for (int body = 0; body < static_cast<int>(freedoms.index.size()); ++body)
    if (freedoms.index[body] >= 0 && !touches[body]) loose.push_back(body);
  return loose;
}

}  // namespace

double largestOpening(const std::vector<Eigen::Vector3d>& position, const std::vector<char>& fixed, double length,
                      const std::vector<ContactCorner>& corners, std::vector<char>* moving) {
  const Freedoms freedoms(position, fixed, length);
  if (moving) moving->assign(fixed.size(), 0);
  if (freedoms.count == 0) return 0.0;
  const auto [x, opening] = mostOpening(contactMatrix(freedoms, corners), static_cast<int>(corners.size()), 6 * freedoms.count);
  if (moving && opening > kOpen)
    for (const BodyMotion& m : motionOf(freedoms, x)) (*moving)[m.body] = 1;
  // A free body that touches nothing is one more way out (as checkInterlocking counts it).
  const std::vector<int> loose = looseBodies(freedoms, corners);
  if (moving)
    for (int body : loose) (*moving)[body] = 1;
  return (opening > kOpen ? opening : 0.0) + static_cast<double>(loose.size());
}

InterlockingVerdict checkInterlocking(const Bundle& bundle, const std::vector<ContactCorner>& corners) {
  const Freedoms freedoms(bundle);
  const int columns = 6 * freedoms.count, rows = static_cast<int>(corners.size());
  InterlockingVerdict verdict;
  if (freedoms.count == 0) {
    verdict.interlocked = true;
    return verdict;
  }
  const std::vector<Eigen::Triplet<double>> triplets = contactMatrix(freedoms, corners);
  Eigen::SparseMatrix<double> a(rows, columns);
  a.setFromTriplets(triplets.begin(), triplets.end());
  const auto [x, opening] = mostOpening(triplets, rows, columns);
  if (opening > kOpen) verdict.motion = motionOf(freedoms, x);
  for (int body : looseBodies(freedoms, corners))
    if (std::none_of(verdict.motion.begin(), verdict.motion.end(), [&](const BodyMotion& m) { return m.body == body; }))
      verdict.motion.push_back({body, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()});
  verdict.interlocked = verdict.motion.empty();
  const SlidingModes sliding = slidingModes(a);
  verdict.slidingModes = sliding.count;
  if (sliding.example.size() > 0) verdict.sliding = motionOf(freedoms, sliding.example);
  return verdict;
}

namespace {

// Rigid-block equilibrium with friction, a feasibility program: per corner the normal force f_n,
// then f_k >= 0 along the edges t_k of the friction pyramid (columns), the free bodies' force and
// moment balances with their weights (rows), and a friction row per corner, sum_k f_k <= mu f_n.
class EquilibriumProgram {
public:
  static constexpr int kSides = 8;  // of the friction pyramid

  EquilibriumProgram(const Bundle& bundle, const Freedoms& freedoms, const std::vector<ContactCorner>& corners)
      : equations_(6 * freedoms.count), count_(static_cast<int>(corners.size())) {
    glp_add_rows(lp_.get(), equations_ + count_);
    // Equilibrium: the contact forces balance the weight.
    const Eigen::VectorXd weight = rigid_blocks::weights(bundle, freedoms);
    for (int row = 0; row < equations_; ++row) glp_set_row_bnds(lp_.get(), row + 1, GLP_FX, weight[row], weight[row]);
    for (int c = 0; c < count_; ++c) glp_set_row_bnds(lp_.get(), equations_ + c + 1, GLP_UP, 0, 0);
    if (count_ > 0) glp_add_cols(lp_.get(), count_ * (kSides + 1));
    std::vector<int> ri, ci;
    std::vector<double> vi;
    for (int c = 0; c < count_; ++c) {
      const ContactCorner& corner = corners[c];
      const Eigen::Vector3d u = corner.normal.unitOrthogonal(), v = corner.normal.cross(u);
      for (int j = 0; j <= kSides; ++j) {
        const double angle = 2 * M_PI * (j - 1) / kSides;
        const Eigen::Vector3d direction = j == 0 ? corner.normal : Eigen::Vector3d(std::cos(angle) * u + std::sin(angle) * v);
        for (const Entry& e : wrench(freedoms, corner, direction)) {
          ri.push_back(e.column);
          ci.push_back(column(c, j));
          vi.push_back(e.value);
        }
      }
    }
    lp_.load(ri, ci, vi);
  }

  /// Feasible at friction mu? At 0 the friction columns are held at 0 (the presolver drops them).
  bool feasibleAt(double mu) {
    std::vector<int> index(kSides + 2);
    std::vector<double> value(kSides + 2);
    for (int c = 0; c < count_; ++c) {
      for (int j = 0; j <= kSides; ++j) {
        index[j + 1] = column(c, j) + 1;
        value[j + 1] = j == 0 ? -mu : 1.0;
        const bool held = j > 0 && mu == 0;
        glp_set_col_bnds(lp_.get(), index[j + 1], held ? GLP_FX : GLP_LO, 0, 0);
      }
      glp_set_mat_row(lp_.get(), equations_ + c + 1, kSides + 1, index.data(), value.data());
    }
    return count_ > 0 && lp_.solveInterior();
  }

  /// The friction the last feasible solution uses: max over corners of sum_k f_k / f_n (<= mu).
  double frictionUsed() const {
    double used = 0;
    for (int c = 0; c < count_; ++c) {
      const double normal = std::max(lp_.primal(column(c, 0) + 1), 1e-300);
      double tangential = 0;
      for (int j = 1; j <= kSides; ++j) tangential += lp_.primal(column(c, j) + 1);
      if (tangential > 1e-12 * normal) used = std::max(used, tangential / normal);
    }
    return used;
  }

private:
  static int column(int corner, int j) { return corner * (kSides + 1) + j; }
  LinearProgram lp_;
  int equations_, count_;
};

// Rigid-block equilibrium's least friction, by bisection to 1 % or 1e-3 (the pyramid is within 8 %
// of the cone): 1e-3 for wedged rigid blocks (any friction, with normal forces growing without
// bound); none when friction 10 does not suffice.
std::optional<double> rigidLeastFriction(EquilibriumProgram& program) {
  double low = 1e-3, high = rigid_blocks::kMostFriction;
  if (!program.feasibleAt(high)) return std::nullopt;
  high = std::min(high, program.frictionUsed());  // the solution at `high` is the last one solved
  if (program.feasibleAt(low)) return low;
  while (high - low > std::max(1e-3, 0.01 * high)) {
    const double mid = 0.5 * (low + high);
    if (program.feasibleAt(mid)) high = std::min(mid, program.frictionUsed());
    else low = mid;
  }
  return high;
}

}  // namespace

StabilityVerdict checkStability(const Bundle& bundle, const AssemblyLevelSets& levelSets, const std::vector<ContactCorner>& corners,
                                bool interlocked, double friction, bool findLeastFriction) {
  StabilityVerdict verdict;
  verdict.stable = true;
  verdict.searched = findLeastFriction;
  verdict.leastFriction = verdict.rigidLeastFriction = 0;
  const Freedoms freedoms(bundle);
  if (freedoms.count == 0) return verdict;
  EquilibriumProgram program(bundle, freedoms, corners);
  if (program.feasibleAt(0)) return verdict;  // frictionless: no admissible motion lowers the weights (Farkas)
  verdict.rigidLeastFriction.reset();
  if (findLeastFriction) verdict.rigidLeastFriction = rigidLeastFriction(program);
  // Friction needed: equilibrium alone would accept forces the unstressed blocks cannot get (a
  // prestress: any friction holds a box between fixed boxes). The settling on the run's contact
  // springs decides; where it neither stands nor shows a fall at the start (its solvers stall, as
  // on the 31 x 31 slab), rigid equilibrium decides an interlocked assembly, whose every
  // admissible motion slides (once the blocks wedge, friction holds them).
  const std::vector<ContactNode> nodes = contactNodes(bundle, levelSets, kTouchFraction * freedoms.length);
  const ElasticSettling settling = settleElastically(bundle, nodes, friction, findLeastFriction);
  verdict.nodes = nodes.size();
  if (!settling.decided && interlocked) {
    verdict.stable = friction > 0 && program.feasibleAt(friction);
    verdict.leastFriction = verdict.rigidLeastFriction;
    return verdict;
  }
  verdict.settled = true;
  verdict.stable = settling.stands;
  verdict.leastFriction = settling.leastFriction;
  verdict.falling = settling.falling;
  return verdict;
}

AssemblyStatics analyseAssembly(const Bundle& bundle, const AssemblyLevelSets& levelSets, double friction, bool findLeastFriction) {
  const auto start = std::chrono::steady_clock::now();
  AssemblyStatics statics;
  const std::vector<ContactCorner> corners = contactPolygons(bundle, levelSets, kTouchFraction * Freedoms(bundle).length);
  std::set<std::pair<int, int>> pairs;
  for (const ContactCorner& c : corners) {
    pairs.insert({c.first, c.second});
    statics.polygons = std::max<std::size_t>(statics.polygons, c.polygon + 1);
  }
  statics.pairs = pairs.size();
  statics.corners = corners.size();
  statics.friction = friction;
  statics.interlocking = checkInterlocking(bundle, corners);
  statics.stability = checkStability(bundle, levelSets, corners, statics.interlocking.interlocked, friction, findLeastFriction);
  statics.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return statics;
}

}  // namespace tessera

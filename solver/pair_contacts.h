#pragma once
#include "geometry/convex_planes.h"
#include "levelset/dense_sdf.h"
#include "levelset/mesh_sdf.h"
#include "levelset/shape.h"
#include "solver/contact_law.h"
#include "solver/contact_parameters.h"
#include "solver/node_bins.h"
#include "solver/node_contacts.h"
#include "solver/obstacles.h"
#include "solver/pair_view.h"
#include "solver/rigid_bodies.h"
#include "solver/travel.h"

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace tessera {

/// What the solver keeps of a shape: its nodes binned, and its level set: the face planes of a
/// convex polyhedron (exact, analytic) when the shape is one, else the exact mesh level set near
/// the surface and the signed-distance grid beyond it.
struct ShapeModel {
  NodeBins nodes;
  DenseSdf sdf;
  std::vector<FacePlane> planes;  ///< body frame; empty: use the grid
  MeshSdf exactMesh;              ///< body frame; empty: the grid near the surface too
  /// Body frame, m: the box around the whole shape (its mesh's vertices and its nodes; the nodes'
  /// own box, nodes.box, can be smaller by up to half a node spacing).
  Eigen::AlignedBox3d box;
  /// m, the farthest point of the shape from its centroid (its mesh's vertices, its nodes): no
  /// point inside it is farther.
  double radius = 0.0;
  /// m^3, the shape's volume: which body is the smaller for one-way evaluation.
  double volume = 0.0;

  /// The level set of a shape without planes at a body-frame point, as gridLevelSet: the exact
  /// mesh level set where the grid's value is within its interpolation error of the surface or
  /// inside, else the grid's value (most candidates are well outside). The grid's nodes hold the
  /// exact phi, which is 1-Lipschitz, so its trilinear interpolation exceeds phi(x) by at most
  /// sum_i w_i |v_i - x| <= (sqrt 3 / 2) h (the cell's centre): a grid value above that is a point
  /// outside, whose value no force uses.
  double meshLevelSet(const Eigen::Vector3d& x, Eigen::Vector3d& normal) const { return meshLevelSet(x, sdf.value(x), normal); }
  /// meshLevelSet with the grid's value at x, sdf.value(x), known. A grid value above
  /// gridValueBound() is the level set itself (outside, no contact); below it the level set needs
  /// this call.
  /// `kept`: the NearestFace of this point's last evaluation, if any (MeshSdf::evaluate).
  double meshLevelSet(const Eigen::Vector3d& x, double gridValue, Eigen::Vector3d& normal,
                      MeshSdf::NearestFace* kept = nullptr) const {
    if (!exactMesh.empty()) {
      const double outside = gridValue;
      if (outside > 0.8660254037844386 * sdf.voxelSize) return outside;
      // (A node of x's cell can prove x outside for less than the search, DenseSdf::provenOutside;
      // the candidates' band has already left out most points it proves, so here it costs more
      // than it saves: 0.94x the wave slab's step without it. candidateValue keeps it.)
      double phi;
      Eigen::Vector3d gradient;
      if (kept != nullptr ? exactMesh.evaluate(x, phi, gradient, *kept) : exactMesh.evaluate(x, phi, gradient)) {
        if (phi < 0) normal = gradient;
        return phi;
      }
    }
    return gridLevelSet(x, gridValue, normal);
  }
  double gridValueBound() const { return exactMesh.empty() ? 0.0 : 0.8660254037844386 * sdf.voxelSize; }

  /// What the candidates of a pair are chosen by, at a body-frame point x of a shape without planes:
  /// a value c(x) such that the level set the solver tests (the grid's, or the exact mesh's where
  /// it has one) is at least c(x) - sqrt(3) |x' - x| at any x'. The grid's trilinear value is
  /// sqrt(3)-Lipschitz (the interpolant of 1-Lipschitz nodes: each partial derivative is at most
  /// 1), and is the value itself; with an exact mesh, a lower bound of the exact phi (1-Lipschitz):
  /// the grid's value less its interpolation error, a corner's proof, or phi.
  double candidateValue(const Eigen::Vector3d& x) const {
    Eigen::Vector3d normal;
    const double gridValue = sdf.value(x);
    if (exactMesh.empty()) return gridLevelSet(x, gridValue, normal);
    if (gridValue > gridValueBound()) return gridValue - gridValueBound();
    const double proven = sdf.provenOutside(x);
    if (proven > 0) return proven;
    double phi;
    if (exactMesh.evaluate(x, phi, normal)) return phi;
    return gridLevelSet(x, gridValue, normal);  // no triangles listed here: the solver takes the grid too
  }

  /// The grid's level set at a body-frame point: phi (m, < 0 inside; positive outside, also
  /// beyond the grid), and when phi < 0 its unit gradient in `normal`. About 1-Lipschitz (to the
  /// interpolation error), which the pairs' candidate bands rely on. (With `planes`, the pair
  /// evaluation uses the exact phi = max_f (n_f . x - d_f) instead.)
  double gridLevelSet(const Eigen::Vector3d& x, Eigen::Vector3d& normal) const { return gridLevelSet(x, sdf.value(x), normal); }
  /// gridLevelSet with sdf.value(x) known.
  double gridLevelSet(const Eigen::Vector3d& x, double gridValue, Eigen::Vector3d& normal) const {
    const double outside = gridValue;  // most candidates are outside: no gradient for them
    if (outside >= 0) return outside;
    const SdfSample s = sdf.sample(x);
    if (s.phi >= 0) return s.phi;
    const double g = s.gradient.norm();
    if (!(g > 0)) return 0.0;  // no direction to push along: treated as touching, no force
    normal = s.gradient / g;
    return s.phi;
  }
};

/// m^2, a node's share of its area projected on the contact plane: share x projection (-n_i . n),
/// 0 where the node faces away (projection <= 0, or NaN). docs/physics.md, "Contact".
inline double facingArea(double share, double projection) { return share * (projection > 0 ? projection : 0.0); }

/// The solver's model of a shape: its nodes binned, its grid, and its exact planes when
/// convex (and exactConvex) or else its exact mesh level set (when exactMesh).
ShapeModel makeShapeModel(const Shape& shape, bool exactConvex, bool exactMesh);

/// The candidate nodes of a pair, sorted by key (as in NodeContact), each quantity in its own
/// array: what a step reads of a node, copied from its body's NodeBins when the candidates are
/// built, so that the step reads them in order instead of gathering them by rank. Side s's
/// candidates are entries [first[s], first[s] + count[s]), followed by padding to a whole block of
/// kBlock entries (position NaN: never inside; key side << 31 | 0x7fffffff, after the side's
/// nodes), so that a step reads them a whole block at a time.
struct CandidateNodes {
  static constexpr int kBlock = 4;  ///< four double lanes
  std::vector<std::uint32_t> key;
  std::vector<double> x, y, z;     ///< m, the node's position in its own body's frame
  std::vector<double> ax, ay, az;  ///< m^2, its whole area times its outward unit normal, same frame
  /// Against a shape with an exact mesh: what each candidate's last exact evaluation kept for the
  /// next (MeshSdf::NearestFace); sized when first used.
  std::vector<MeshSdf::NearestFace> nearestFace;
  /// Per block of kBlock entries: which of them were inside the other side at the last evaluation
  /// (bit j: entry j of the block; 0xff before the first). The same bits every block at the next
  /// evaluation: the same contacts as then, in the same order.
  std::vector<std::uint8_t> inside;
  int first[2] = {0, 0}, count[2] = {0, 0};

  /// Entries, with the padding.
  std::size_t size() const { return key.size(); }
  /// Candidate nodes, both sides.
  int nodes() const { return count[0] + count[1]; }
  void clear() {
    key.clear();
    for (std::vector<double>* v : {&x, &y, &z, &ax, &ay, &az}) v->clear();
    nearestFace.clear();
    inside.clear();
    first[0] = first[1] = count[0] = count[1] = 0;
  }
  /// Side `side`'s candidates begin: add() them, then endSide().
  void beginSide(std::uint32_t side) { first[side] = static_cast<int>(size()); }
  /// Side `side`'s candidates end: counted and padded.
  void endSide(std::uint32_t side) {
    count[side] = static_cast<int>(size()) - first[side];
    while (size() % kBlock != 0) {
      key.push_back(side << 31 | 0x7fffffffu);
      for (std::vector<double>* v : {&x, &y, &z, &ax, &ay, &az}) v->push_back(NAN);
    }
    inside.resize(size() / kBlock, 0xff);
  }
  /// Node `rank` of `nodes`, with its key.
  void add(std::uint32_t nodeKey, const NodeBins& nodes, int rank) {
    key.push_back(nodeKey);
    const Eigen::Vector3d &p = nodes.position[rank], &n = nodes.normal[rank];
    x.push_back(p.x());
    y.push_back(p.y());
    z.push_back(p.z());
    const double area = nodes.area[rank];
    ax.push_back(area * n.x());
    ay.push_back(area * n.y());
    az.push_back(area * n.z());
  }
};

/// One candidate pair and its contact state. `b` >= 0 is a body; `b` < 0 an obstacle: sphere
/// -1 - k, or plane -1 - spheres - k (the numbering of the result files). Forces from the last
/// evaluation; torques about each body's centroid; for an obstacle, forceB is the reaction on it.
struct PairContacts {
  int a = -1, b = -1;
  PairKind kind = PairKind::Bodies;  ///< pairKind(b, spheres)
  /// This pair's k_n over the scene's (1 under the span rule; the bar rule's, World::stiffnessScale).
  double stiffnessScale = 1.0;
  NodeContacts contacts;  ///< of the last evaluation
  /// During an evaluation, the contacts of the one before (their history); between evaluations,
  /// spare arrays (no allocation per step).
  NodeContacts previous;
  /// The nodes within the candidate band of the other side when the candidates were last built;
  /// only these can touch until the two sides have moved by candidateMotion() >= band / sqrt(3)
  /// relative to each other (then they are built again).
  CandidateNodes candidates;
  bool candidatesValid = false;  ///< false: the next evaluation visits every node in range and rebuilds them
  /// For each side's candidates against a convex other side: the other side's face planes that can
  /// give a candidate its level set until the candidates are built again (bit f: plane f; the
  /// others lie below by more than the sides can move meanwhile), found when they are built.
  std::uint64_t planesKept[2] = {~0ull, ~0ull};
  /// World poses when the candidates were built: body a's centroid and orientation, and the other
  /// side's (body b's; a sphere's centre; a plane's point), for candidateMotion().
  Eigen::Vector3d builtPositionA{0, 0, 0}, builtPositionB{0, 0, 0};
  Eigen::Quaterniond builtOrientationA = Eigen::Quaterniond::Identity(), builtOrientationB = Eigen::Quaterniond::Identity();
  /// The last exact candidateMotion(), m, and the two sides' summed Travel then: the motion since
  /// the candidates were built is at most checkedMotion + (travel now - checkedTravel), so the
  /// exact motion is computed again only once that bound reaches the rebuild threshold.
  double checkedMotion = 0.0, checkedTravel = 0.0;
  Eigen::Vector3d forceA{0, 0, 0}, torqueA{0, 0, 0}, forceB{0, 0, 0}, torqueB{0, 0, 0};
  Eigen::Vector3d normalForceA{0, 0, 0};  ///< N, the part of forceA along the contact normals (forceA minus it: friction)
  Eigen::Vector3d forcePoint{0, 0, 0};  ///< m, world: contact points weighted by normal force (force chains)
  ContactTally tally;          ///< stored and dissipated energy, sliding nodes, of the last evaluation
  double maxDepth = 0.0;       ///< m, deepest node penetration
  long evaluations = 0;        ///< node-vs-level-set evaluations in the last evaluation (for benchmarks)
};

/// The pairs' order by their bodies (a, b): the World's list after updatePairs, and the implicit
/// method's copy of the pairs at an increment's start.
inline bool pairsByBodies(const PairContacts& x, const PairContacts& y) {
  return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
}

/// The scene as a pair evaluation needs it (read-only during evaluation).
struct ContactScene {
  const RigidBodies* bodies;
  const BodyKinematics* kinematics;  ///< of `bodies`, this step
  const std::vector<ShapeModel>* shapes;
  const std::vector<SphereObstacle>* spheres;
  const std::vector<PlaneObstacle>* planes;
  ContactParameters parameters;
  double kn = 0.0, kt = 0.0;  ///< N/m^3
  double dt = 0.0;            ///< s
  /// m: a node farther than this outside the other side's level set when the pair's candidates
  /// are built is not a candidate; they are built again before the sides have moved 1 / sqrt(3) of
  /// it relative to each other (candidateMotion; every level set here is at most sqrt(3)-Lipschitz),
  /// so no other node can reach contact.
  double candidateBand = 0.0;
  /// Of the bodies and spheres, to this evaluation; null: each pair computes its exact motion.
  const Travel* travel = nullptr;
};

/// k_n and k_t of a pair, N/m^3: the scene's times the pair's stiffnessScale and `factor` (an
/// obstacle's); a k_t given absolute (N/m^3) is the scene's whatever the pair.
inline std::pair<double, double> pairStiffness(const ContactParameters& p, double kn, double kt, double scale, double factor) {
  return {kn * scale * factor, kt * (p.tangentialStiffnessAbsolute > 0 ? 1.0 : scale) * factor};
}

/// The kind of the pair (a, b) in a World with `spheres` spheres.
inline PairKind pairKind(int b, int spheres) {
  return b >= 0 ? PairKind::Bodies : -1 - b < spheres ? PairKind::Sphere : PairKind::Plane;
}

/// m, an upper bound on how far any node of either side of the pair has moved, in the other
/// side's frame, since its candidates were built: a rigid motion moves a point x of body M by at
/// most |dp_M| + 2 sin(theta_M / 2) |x - c_M| (theta_M the angle M turned: the chord of the arc),
/// and a point near O in O's frame by at most |dp_O| + 2 sin(theta_O / 2) r_O, so the bound is the
/// sum of |dp| + 2 sin(theta / 2) r over both sides (r: ShapeModel::radius; an obstacle does not
/// turn).
double candidateMotion(const ContactScene& scene, const PairContacts& pair);

/// Evaluates one pair, by its kind. Each keeps the springs of nodes still in contact and drops
/// the others, and visits only the pair's candidate nodes, rebuilding them first when they are
/// not valid. Thread-safe for distinct pairs.
void evaluatePair(const ContactScene& scene, PairContacts& pair);
/// Two bodies: the nodes of each in the other's level set (its exact planes when convex, else its
/// grid), each node with half its area, so that the pair does not depend on which body is a and a
/// flat face-on-face contact carries exactly k_n d.
void evaluateBodyPair(const ContactScene& scene, PairContacts& pair);
/// A body against a sphere (the indenter): the body's nodes with their full area, the sphere's
/// stiffnesses scaled by its stiffnessFactor.
void evaluateSpherePair(const ContactScene& scene, PairContacts& pair);
/// A body against a plane: the body's nodes with their full area.
void evaluatePlanePair(const ContactScene& scene, PairContacts& pair);

}  // namespace tessera

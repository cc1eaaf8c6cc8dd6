#include "solver/world.h"

#include "geometry/convex_planes.h"
#include "solver/broad_phase.h"
#include "solver/world_internals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace tessera {

ShapeModel makeShapeModel(const Shape& shape, bool exactConvex, bool exactMesh) {
  ShapeModel m;
  m.nodes = makeNodeBins(shape.nodes);
  m.sdf = shape.sdf;
  if (exactConvex && shape.convex) m.planes = shape.convex->planes;
  if (m.planes.size() > static_cast<std::size_t>(kMaxConvexPlanes))
    throw std::invalid_argument("shape '" + shape.name + "': " + std::to_string(m.planes.size()) +
                                " convex planes, more than the " + std::to_string(kMaxConvexPlanes) +
                                " the solver holds; prepare it again (tessera prep) to use its level-set grid");
  if (exactMesh && m.planes.empty()) m.exactMesh = shape.exactMesh;
  m.volume = shape.mass.volume;
  for (const auto* points : {&shape.nodes.positions, &shape.mesh.vertices})
    for (const Eigen::Vector3d& x : *points) {
      m.box.extend(x);
      m.radius = std::max(m.radius, x.norm());
    }
  return m;
}

namespace {

// An upper estimate of the fastest mode of a free body: every node of its surface in sticking
// contact with a body like itself moving the other way (the checkerboard mode of a packed
// assembly; Gershgorin's bound on the mass-normalised stiffness matrix doubles each body's own
// stiffness). Along and about each principal axis e_k, over all nodes (docs/physics.md, "Time step"):
//   K_k = k_n sum a (n.e_k)^2 + k_t sum a (1 - (n.e_k)^2)                        omega^2 = 2 K_k / m
//   G_k = k_n sum a ((e_k x r).n)^2 + k_t sum a (|e_k x r|^2 - ((e_k x r).n)^2)    omega^2 = 2 G_k / I_k
// (k_t counts only with friction; without it no tangential force acts.) Translation-rotation
// coupling is left out: the measured critical steps (bench/stability_map.cpp) bound what that costs.
// kn, kt: the stiffest contact the body can have, N/m^3.
double fastestMode(const Shape& shape, double mass, const Eigen::Vector3d& inertia, const ContactParameters& p, double kn,
                   double kt) {
  double omega2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
    double translation = 0.0, rotation = 0.0;
    for (std::size_t i = 0; i < shape.nodes.size(); ++i) {
      const Eigen::Vector3d& n = shape.nodes.normals[i];
      const double a = p.perNodeStiffness > 0 ? p.perNodeStiffness / kn : shape.nodes.areas[i];
      const double cn = n.dot(e);
      const Eigen::Vector3d lever = e.cross(shape.nodes.positions[i]);
      const double cr = lever.dot(n);
      translation += a * (kn * cn * cn + kt * (1 - cn * cn));
      rotation += a * (kn * cr * cr + kt * (lever.squaredNorm() - cr * cr));
    }
    omega2 = std::max({omega2, 2 * translation / mass, 2 * rotation / inertia[k]});
  }
  return std::sqrt(omega2);
}

std::string format(const char* pattern, double a, double b = 0, double c = 0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
  return buffer;
}

}  // namespace

World::World(const std::vector<Shape>& shapes, const std::vector<Body>& bodies, const ContactParameters& parameters,
             const SolverSettings& settings)
    : parameters_(parameters), settings_(settings), arena_(std::make_unique<ThreadArena>(settings.threads)) {
  if (!(parameters.normalStiffness() > 0)) throw std::invalid_argument("contact stiffness E M / L must be positive");
  if (!(settings.density > 0)) throw std::invalid_argument("density must be positive");
  if (settings.localDamping < 0 || settings.localDamping >= 1)
    throw std::invalid_argument("local damping must lie in [0, 1)");
  for (const Shape& s : shapes) shapes_.push_back(makeShapeModel(s, settings.exactConvexLevelSets, settings.exactMeshLevelSets));
  state_.bodies = makeRigidBodies(shapes, bodies, settings.density);
  {
    std::vector<TriangleMesh> meshes;
    for (const Shape& s : shapes) meshes.push_back(s.mesh);
    bars_ = ContactBars(meshes, state_.bodies.shape, state_.bodies.position, state_.bodies.orientation, state_.bodies.fixed,
                        parameters.stiffnessRule == StiffnessRule::Sections);
  }

  double omega = 0.0, thinnest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < state_.bodies.size(); ++i) {
    const Shape& shape = shapes[state_.bodies.shape[i]];
    thinnest = std::min(thinnest, boundingBox(shape.mesh.vertices).sizes().minCoeff());
    if (state_.bodies.fixed[i]) continue;
    // The stiffest contact: k_n = E M / L (span), or E over the body's shortest bar (bars; under
    // the section rule that bar times the body's least section factor, ContactBars::shortest).
    const double scale = parameters.stiffnessRule != StiffnessRule::Span
                             ? parameters.youngsModulus / bars_.shortest(static_cast<int>(i)) / parameters.normalStiffness()
                             : 1.0;
    const auto [kn, kt] = pairStiffness(parameters, parameters.normalStiffness(),
                                        parameters.friction > 0 ? parameters.tangentialStiffness() : 0.0, scale, 1.0);
    omega = std::max(omega, fastestMode(shape, state_.bodies.mass[i], state_.bodies.inertia[i], parameters, kn, kt));
  }
  automaticDt_ = omega > 0 ? settings.timeStepFactor * 2.0 / omega : 1e-6;
  dt_ = settings.timeStep > 0 ? settings.timeStep : automaticDt_;
  const double limit = omega > 0 ? 2.0 / omega : std::numeric_limits<double>::infinity();
  if (dt_ > limit * (1 + 1e-12) && !settings.allowUnsafeTimeStep)
    throw std::invalid_argument(format("time step %.4g s is above the stability estimate 2 / omega_max = %.4g s "
                                       "for this assembly and material; use a smaller time step, or 0 (automatic)",
                                       dt_, limit));
  // As small a step as time_step_factor allows, and no smaller: below, a run only costs more steps.
  if (settings.timeStep > 0 && omega > 0 && dt_ < 1e-4 * limit)
    throw std::invalid_argument(format("time step %.4g s is below 1e-4 of the stability estimate %.4g s: the run would "
                                       "take over 10 000 times the steps it needs; use 0 (automatic)", dt_, limit));
  thinnest_ = thinnest;
  penetrationLimit_ = settings.maxPenetration > 0 ? settings.maxPenetration : 0.25 * thinnest;
  if (!(settings_.broadPhaseMargin > 0)) settings_.broadPhaseMargin = settings.broadPhaseMarginRatio * thinnest;

  const std::size_t n = state_.bodies.size();
  state_.force.assign(n, Eigen::Vector3d::Zero());
  state_.torque.assign(n, Eigen::Vector3d::Zero());
  state_.contactForce.assign(n, Eigen::Vector3d::Zero());
  state_.contactTorque.assign(n, Eigen::Vector3d::Zero());
  state_.dampingForce.assign(n, Eigen::Vector3d::Zero());
  state_.dampingTorque.assign(n, Eigen::Vector3d::Zero());
  state_.startPosition = state_.bodies.position;
  for (std::size_t i = 0; i < n; ++i) bodyRadius_.push_back(shapes_[state_.bodies.shape[i]].radius);
  if (settings_.method == SolverMethod::Implicit) {
    const ImplicitSettings& s = settings_.implicit;
    if (!(s.tolerance > 0) || !(s.maxIterations > 0) || !(s.maxIncrement >= 0) || !(s.maxTravel >= 0) || !(s.maxTravelRatio > 0))
      throw std::invalid_argument("implicit settings: tolerance, iterations and travel ratio must be positive, limits 0 or positive");
    dt_ = implicitIncrementLimit();  // until the first increment
  }
}

namespace {

// What a PairState keeps of a pair, once for both directions: `both(x, y)` is called with each
// field of the solver's pair and its PairState's.
template <class Pair, class State, class Both>
void pairStateFields(Pair& p, State& q, Both&& both) {
  both(p.a, q.a);
  both(p.b, q.b);
  both(p.forceA, q.forceA);
  both(p.torqueA, q.torqueA);
  both(p.forceB, q.forceB);
  both(p.torqueB, q.torqueB);
  both(p.tally.elastic, q.elastic);
  both(p.maxDepth, q.depth);
}

}  // namespace

WorldState World::state() const {
  WorldState s;
  static_cast<WorldRunState&>(s) = state_;
  for (const PairContacts& p : pairs_) {
    PairState& q = s.pairs.emplace_back();
    pairStateFields(p, q, [](const auto& from, auto& to) { to = from; });
    for (const NodeContact& c : p.contacts) q.contacts.push_back(c);
  }
  return s;
}

namespace {

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }
bool unit(const Eigen::Quaterniond& q) { return q.coeffs().allFinite() && std::abs(q.norm() - 1.0) < 1e-6; }

template <class T, class Valid>
void requireEach(const std::vector<T>& values, std::size_t size, bool orEmpty, const char* what, Valid&& valid) {
  if (values.size() != size && !(orEmpty && values.empty()))
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(values.size()) + " values for " + std::to_string(size));
  for (const T& v : values)
    if (!valid(v)) throw std::invalid_argument(std::string(what) + ": a value is not finite (or not a unit quaternion)");
}

}  // namespace

// A state from a file is checked whole before it replaces this World's: sizes against the bodies,
// pair indices against the bodies and obstacles, contact keys against the nodes, every number finite.
void World::checkState(const WorldState& s) const {
  const std::size_t n = state_.bodies.size();
  requireEach(s.bodies.position, n, false, "positions", finite);
  requireEach(s.bodies.orientation, n, false, "orientations", unit);
  requireEach(s.bodies.velocity, n, false, "velocities", finite);
  requireEach(s.bodies.angularMomentum, n, false, "angular momenta", finite);
  requireEach(s.bodies.fixed, n, false, "fixed flags", [](char) { return true; });
  requireEach(s.bodies.retired, n, false, "retired flags", [](char) { return true; });
  for (const auto* v : {&s.force, &s.torque, &s.contactForce, &s.contactTorque, &s.dampingForce, &s.dampingTorque,
                        &s.startPosition})
    requireEach(*v, n, false, "per-body vectors", finite);
  // The broad phase's build poses exist once it has been built (pairsValid).
  requireEach(s.builtPosition, n, !s.pairsValid, "build positions", finite);
  requireEach(s.builtOrientation, n, !s.pairsValid, "build orientations", unit);
  for (const SphereObstacle& sphere : s.spheres)
    if (!finite(sphere.center) || !finite(sphere.velocity) || !(sphere.radius > 0) || !std::isfinite(sphere.radius) ||
        !(sphere.stiffnessFactor > 0) || !std::isfinite(sphere.stiffnessFactor))
      throw std::invalid_argument("an indenter with a non-finite or non-positive value");
  requireEach(s.sphereReaction, s.spheres.size(), false, "indenter reactions", finite);
  requireEach(s.builtSphereCentre, s.spheres.size(), !s.pairsValid, "indenter positions", finite);
  const int obstacles = static_cast<int>(s.spheres.size() + s.planes.size());
  for (const PairState& p : s.pairs) {
    if (p.a < 0 || p.a >= static_cast<int>(n) || p.b < -obstacles || p.b >= static_cast<int>(n) || p.a == p.b)
      throw std::invalid_argument("a contact pair (" + std::to_string(p.a) + ", " + std::to_string(p.b) + ") names no body");
    for (const NodeContact& c : p.contacts) {
      const int body = (c.key >> 31) == 0 ? p.a : p.b;
      const std::size_t nodes = body >= 0 ? shapes_[state_.bodies.shape[body]].nodes.position.size() : 0;
      if ((body >= 0 && (c.key & 0x7fffffffu) >= nodes) || !finite(c.spring) || !std::isfinite(c.energy) || !std::isfinite(c.area))
        throw std::invalid_argument("a contact names no node, or holds a non-finite value");
    }
    if (!finite(p.forceA) || !finite(p.torqueA) || !finite(p.forceB) || !finite(p.torqueB) || !std::isfinite(p.elastic) ||
        !std::isfinite(p.depth))
      throw std::invalid_argument("a contact pair holds a non-finite force or energy");
  }
  for (double e : {s.initialEnergy, s.externalWork, s.friction, s.damping, s.retiredKinetic, s.projection, s.mostSupplied, s.time})
    if (!std::isfinite(e)) throw std::invalid_argument("an energy or the time is not finite");
  if (s.time < 0 || s.steps < 0) throw std::invalid_argument("a negative time or step count");
  const ImplicitCounts& c = s.implicit;
  if (!std::isfinite(c.increment) || c.increment < 0 || !(c.travelFactor >= 1) || !(c.travelFactor <= settings_.implicit.maxTravelGrowth) ||
      !(c.largestReaction >= 0) || !std::isfinite(c.largestReaction) || c.iterations < 0 || c.cutbacks < 0 || c.dynamicIncrements < 0)
    throw std::invalid_argument("the implicit method's increment or counts are negative or not finite");
}

void World::restore(const WorldState& s) {
  checkState(s);
  state_ = s;
  // The pairs from their saved state; their candidate nodes are built again at the next
  // evaluation, and (the travel the state's World measured is not this one's) every pair computes
  // its exact candidate motion then.
  pairs_.clear();
  for (const PairState& q : s.pairs) {
    PairContacts& p = pairs_.emplace_back();
    pairStateFields(p, q, [](auto& to, const auto& from) { to = from; });
    p.contacts.assign(q.contacts);
    p.kind = pairKind(p.b, static_cast<int>(state_.spheres.size()));
    p.checkedTravel = -std::numeric_limits<double>::infinity();
    p.stiffnessScale = stiffnessScale(p);
  }
}

int World::pairCount() const { return static_cast<int>(pairs_.size()); }

PairView World::pair(int k) const {
  const PairContacts& p = pairs_.at(k);
  PairView v;
  v.a = p.a;
  v.b = p.b;
  v.kind = p.kind;
  v.force = p.forceA;
  v.torque = p.torqueA;
  v.normalForce = p.normalForceA;
  v.point = p.forcePoint;
  v.nodeContacts = static_cast<int>(p.contacts.size());
  v.slidingNodes = p.tally.sliding;
  for (const NodeContact& c : p.contacts) v.area += c.area;
  v.elastic = p.tally.elastic;
  v.depth = p.maxDepth;
  v.normalStiffness = normalStiffness(p);
  return v;
}

namespace {

void requireMoving(const RigidBodies& bodies, int i, const char* what) {
  if (i < 0 || i >= static_cast<int>(bodies.size()) || !bodies.moves(i))
    throw std::invalid_argument(std::string(what) + ": body " + std::to_string(i) + " is not a free body of this World");
}

}  // namespace

void World::setPose(int i, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation) {
  requireMoving(state_.bodies, i, "setPose");
  if (!position.allFinite() || !orientation.coeffs().allFinite() || std::abs(orientation.norm() - 1) > 1e-9)
    throw std::invalid_argument("setPose: a position that is not finite or an orientation that is not a unit quaternion");
  // Before the first step the body is simply built there (gravity's work counts from here);
  // after it the books are open: whatever the jump changes in them (the energy stored in the
  // contacts, gravity's work) is booked as supplied, from the forces evaluated at once at the new
  // pose, so that the residual does not move.
  const double residual = state_.steps > 0 ? energy().residual() : 0.0;
  state_.bodies.position[i] = position;
  state_.bodies.orientation[i] = orientation;
  state_.pairsValid = state_.forcesValid = false;
  if (state_.steps == 0) {
    state_.startPosition[i] = position;
    return;
  }
  evaluateForces(0.0);
  state_.initialEnergy += residual - energy().residual();
}

void World::setVelocity(int i, const Eigen::Vector3d& velocity, const Eigen::Vector3d& angularMomentum) {
  requireMoving(state_.bodies, i, "setVelocity");
  if (!velocity.allFinite() || !angularMomentum.allFinite())
    throw std::invalid_argument("setVelocity: a velocity or angular momentum that is not finite");
  const double kinetic = state_.bodies.kineticEnergy(i);
  state_.bodies.velocity[i] = velocity;
  state_.bodies.angularMomentum[i] = angularMomentum;
  state_.forcesValid = false;
  if (state_.steps > 0) state_.initialEnergy += state_.bodies.kineticEnergy(i) - kinetic;  // supplied, as setPose books
}

void World::retireBody(int i) {
  if (state_.bodies.retired[i]) return;
  state_.retiredKinetic += state_.bodies.kineticEnergy(i);
  state_.bodies.retired[i] = 1;
  state_.bodies.velocity[i].setZero();
  state_.bodies.angularMomentum[i].setZero();
  state_.pairsValid = state_.forcesValid = false;
}

World::~World() = default;

Eigen::AlignedBox3d World::bodyBox(int i, double margin) const {
  return worldBox(shapes_[state_.bodies.shape[i]].box, state_.bodies.orientation[i], state_.bodies.position[i], margin);
}

double World::bodySize(int i) const { return shapes_[state_.bodies.shape[i]].box.sizes().minCoeff(); }

int World::addSphere(const SphereObstacle& sphere) {
  state_.spheres.push_back(sphere);
  state_.sphereReaction.push_back(Eigen::Vector3d::Zero());
  state_.pairsValid = state_.forcesValid = false;
  return static_cast<int>(state_.spheres.size()) - 1;
}

int World::addPlane(const PlaneObstacle& plane) {
  state_.planes.push_back(plane);
  state_.planes.back().normal.normalize();
  state_.pairsValid = state_.forcesValid = false;
  return static_cast<int>(state_.planes.size()) - 1;
}

// Candidate pairs from boxes enlarged by the margin m, rebuilt only when a body (or sphere) has
// moved or turned (turnChord x radius) by more than 0.4 m since the last build; contact states,
// and node candidates, carry over by pair key. Each pair builds its node candidates again on its own,
// when its two sides have moved relative to each other by band / sqrt(3) (evaluatePair).
double World::candidateBand() const { return 1.25 * settings_.broadPhaseMargin; }

void World::updatePairs() {
  const double margin = settings_.broadPhaseMargin;
  if (state_.pairsValid) {
    bool moved = false;
    for (std::size_t i = 0; i < state_.bodies.size() && !moved; ++i) {
      if (!state_.bodies.moves(i)) continue;
      const double turn = turnChord(state_.bodies.orientation[i], state_.builtOrientation[i]) * shapes_[state_.bodies.shape[i]].radius;
      moved = (state_.bodies.position[i] - state_.builtPosition[i]).norm() + turn > 0.4 * margin;
    }
    for (std::size_t k = 0; k < state_.spheres.size() && !moved; ++k)
      moved = (state_.spheres[k].center - state_.builtSphereCentre[k]).norm() > 0.4 * margin;
    if (!moved) return;
  }

  std::vector<Eigen::AlignedBox3d> boxes;
  for (std::size_t i = 0; i < state_.bodies.size(); ++i)
    boxes.push_back(state_.bodies.retired[i] ? Eigen::AlignedBox3d()  // empty: intersects nothing
                                : worldBox(shapes_[state_.bodies.shape[i]].box, state_.bodies.orientation[i], state_.bodies.position[i], margin));
  std::vector<std::pair<int, int>> wanted = sweepPairs(boxes, state_.bodies.fixed);
  const int sphereCount = static_cast<int>(state_.spheres.size());
  const bool spheresAdded = static_cast<int>(state_.builtSphereCentre.size()) != sphereCount;  // since the last build
  for (int k = 0; k < sphereCount; ++k) {
    const Eigen::AlignedBox3d box(state_.spheres[k].center.array() - state_.spheres[k].radius - margin,
                                  state_.spheres[k].center.array() + state_.spheres[k].radius + margin);
    for (int i = 0; i < static_cast<int>(state_.bodies.size()); ++i)
      if (boxes[i].intersects(box)) wanted.emplace_back(i, -1 - k);
  }
  for (int k = 0; k < static_cast<int>(state_.planes.size()); ++k)
    for (int i = 0; i < static_cast<int>(state_.bodies.size()); ++i)
      if (state_.bodies.moves(i)) wanted.emplace_back(i, -1 - sphereCount - k);
  std::sort(wanted.begin(), wanted.end());

  // Keep the state of pairs that stay candidates (both lists sorted by (a, b)).
  std::vector<PairContacts> next;
  next.reserve(wanted.size());
  std::sort(pairs_.begin(), pairs_.end(), pairsByBodies);
  std::size_t old = 0;
  for (const auto& [a, b] : wanted) {
    while (old < pairs_.size() && std::make_pair(pairs_[old].a, pairs_[old].b) < std::make_pair(a, b)) ++old;
    if (old < pairs_.size() && pairs_[old].a == a && pairs_[old].b == b) {
      next.push_back(std::move(pairs_[old]));
      // An obstacle's number shifts when a sphere is added before the planes: its kind is
      // found again, and a pair that changed kind, or names another plane, starts without contact
      // history or candidates.
      const bool otherPlane = next.back().kind == PairKind::Plane && spheresAdded;
      if (next.back().kind != pairKind(b, sphereCount) || otherPlane) {
        next.back().kind = pairKind(b, sphereCount);
        next.back().contacts.clear();
        next.back().candidatesValid = false;
        next.back().stiffnessScale = stiffnessScale(next.back());
      }
    } else {
      PairContacts pair;
      pair.a = a;
      pair.b = b;
      pair.kind = pairKind(b, sphereCount);
      pair.stiffnessScale = stiffnessScale(pair);
      next.push_back(std::move(pair));
    }
  }
  pairs_ = std::move(next);
  state_.builtPosition = state_.bodies.position;
  state_.builtOrientation = state_.bodies.orientation;
  state_.builtSphereCentre.clear();
  for (const auto& s : state_.spheres) state_.builtSphereCentre.push_back(s.center);
  state_.pairsValid = true;
}

// The pair's k_n over E M / L: 1 under the span rule; under the bar and section rules E / (w_a + w_b) over it
// (ContactBars: the indenter comes down along -z, so it meets a body's top; a plane meets the
// body's side facing it).
double World::stiffnessScale(const PairContacts& pair) const {
  if (parameters_.stiffnessRule == StiffnessRule::Span) return 1.0;
  double bars = 0.0;
  switch (pair.kind) {
    case PairKind::Bodies: bars = bars_.betweenBodies(pair.a, pair.b); break;
    case PairKind::Sphere: bars = bars_.againstObstacle(pair.a, Eigen::Vector3d::UnitZ()); break;
    case PairKind::Plane:
      bars = bars_.againstObstacle(pair.a, -state_.planes[-1 - pair.b - static_cast<int>(state_.spheres.size())].normal);
      break;
  }
  return parameters_.youngsModulus / bars / parameters_.normalStiffness();
}

double World::normalStiffness(const PairContacts& pair) const {
  const double factor = pair.kind == PairKind::Sphere ? state_.spheres[-1 - pair.b].stiffnessFactor : 1.0;
  return parameters_.normalStiffness() * pair.stiffnessScale * factor;
}

// springStep: the time since the springs were last loaded, s: the step's dt after a drift, 0 when
// the forces are evaluated again at the same configuration (after retireBody or addSphere, or at
// the start), so that no spring is loaded twice by the same motion.
void World::evaluateForces(double springStep) {
  updatePairs();
  kinematics_.update(state_.bodies);
  travel_.update(state_.bodies, bodyRadius_, state_.spheres);
  ContactScene scene{&state_.bodies, &kinematics_, &shapes_, &state_.spheres, &state_.planes, parameters_,
                     parameters_.normalStiffness(), parameters_.tangentialStiffness(), springStep, candidateBand(), &travel_};
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs_.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t p = r.begin(); p != r.end(); ++p) evaluatePair(scene, pairs_[p]);
    });
  });

  // Reduce per body in pair order: the same sums in the same order for any thread count.
  std::fill(state_.contactForce.begin(), state_.contactForce.end(), Eigen::Vector3d::Zero());
  std::fill(state_.contactTorque.begin(), state_.contactTorque.end(), Eigen::Vector3d::Zero());
  std::fill(state_.sphereReaction.begin(), state_.sphereReaction.end(), Eigen::Vector3d::Zero());
  for (const PairContacts& pair : pairs_) {
    state_.friction += pair.tally.friction;
    state_.damping += pair.tally.viscous;
    state_.projection += pair.tally.projection;
    state_.contactForce[pair.a] += pair.forceA;
    state_.contactTorque[pair.a] += pair.torqueA;
    switch (pair.kind) {
      case PairKind::Bodies:
        state_.contactForce[pair.b] += pair.forceB;
        state_.contactTorque[pair.b] += pair.torqueB;
        break;
      case PairKind::Sphere: state_.sphereReaction[-1 - pair.b] += pair.forceB; break;
      case PairKind::Plane: break;  // fixed: its reaction is not needed
    }
  }

  // Gravity and damping (docs/physics.md, "Damping").
  const double alpha = settings_.localDamping, c = settings_.viscousDamping;
  for (std::size_t i = 0; i < state_.bodies.size(); ++i) {
    const Eigen::Vector3d f = state_.contactForce[i] + state_.bodies.mass[i] * settings_.gravity;
    const Eigen::Vector3d& t = state_.contactTorque[i];
    Eigen::Vector3d fd = Eigen::Vector3d::Zero(), td = Eigen::Vector3d::Zero();
    if (state_.bodies.moves(i)) {
      const Eigen::Vector3d v = state_.bodies.velocity[i], w = state_.bodies.angularVelocity(i);
      if (c > 0) {
        fd -= c * state_.bodies.mass[i] * v;
        td -= c * (state_.bodies.orientation[i] * state_.bodies.angularMomentum[i]);  // c I omega = c L
      }
      if (alpha > 0)
        for (int k = 0; k < 3; ++k) {
          fd[k] -= alpha * std::abs(f[k] + fd[k]) * (v[k] > 0 ? 1.0 : v[k] < 0 ? -1.0 : 0.0);
          td[k] -= alpha * std::abs(t[k] + td[k]) * (w[k] > 0 ? 1.0 : w[k] < 0 ? -1.0 : 0.0);
        }
    }
    state_.dampingForce[i] = fd;
    state_.dampingTorque[i] = td;
    state_.force[i] = f + fd;
    state_.torque[i] = t + td;
  }
  state_.forcesValid = true;
}

// Velocity Verlet (kick-drift-kick) for translation; the rotation drift is the free-rotor
// splitting of rotateFreely, with torque kicks in the body frame on either side (docs/physics.md).
void World::step() {
  if (settings_.method == SolverMethod::Implicit) return implicitStep();
  explicitStep();
}

void World::explicitStep() {
  if (!state_.forcesValid) {
    evaluateForces(0.0);
    if (state_.steps == 0) {
      const EnergyBudget e = energy();
      state_.initialEnergy = e.kinetic + e.elastic;
    }
  }
  const double h = 0.5 * dt_;
  // A half kick of body i; the damping forces' work over it, exactly as the kick changes the
  // kinetic energy: h f . (v_before + v_after) / 2 (and h tau . omega_mean for the rotation).
  const auto kick = [&](std::size_t i) {
    const Eigen::Vector3d v0 = state_.bodies.velocity[i], L0 = state_.bodies.angularMomentum[i];
    state_.bodies.velocity[i] += h * state_.force[i] / state_.bodies.mass[i];
    state_.bodies.angularMomentum[i] += h * (state_.bodies.orientation[i].conjugate() * state_.torque[i]);
    if (state_.dampingForce[i].isZero() && state_.dampingTorque[i].isZero()) return;
    const Eigen::Vector3d omega = state_.bodies.orientation[i] * (0.5 * (L0 + state_.bodies.angularMomentum[i])).cwiseQuotient(state_.bodies.inertia[i]);
    state_.damping -= h * (state_.dampingForce[i].dot(0.5 * (v0 + state_.bodies.velocity[i])) + state_.dampingTorque[i].dot(omega));
  };
  for (std::size_t i = 0; i < state_.bodies.size(); ++i) {
    if (!state_.bodies.moves(i)) continue;
    kick(i);
    state_.bodies.position[i] += dt_ * state_.bodies.velocity[i];
  }
  rotateFreely(state_.bodies, dt_);
  for (std::size_t k = 0; k < state_.spheres.size(); ++k) {
    // Work of the prescribed motion on the bodies over this step (reaction from the last evaluation).
    state_.externalWork += -state_.sphereReaction[k].dot(state_.spheres[k].velocity) * dt_;
    state_.spheres[k].center += dt_ * state_.spheres[k].velocity;
  }
  evaluateForces(dt_);
  for (std::size_t i = 0; i < state_.bodies.size(); ++i)
    if (state_.bodies.moves(i)) kick(i);
  state_.time += dt_;
  ++state_.steps;
  checkStability();
}

EnergyBudget World::energy() const {
  EnergyBudget e;
  for (std::size_t i = 0; i < state_.bodies.size(); ++i) {
    // Every body: a retired one keeps the gravity work done on it until it was frozen.
    e.gravityWork += state_.bodies.mass[i] * settings_.gravity.dot(state_.bodies.position[i] - state_.startPosition[i]);
    if (state_.bodies.moves(i)) e.kinetic += state_.bodies.kineticEnergy(i);
  }
  for (const PairContacts& p : pairs_) e.elastic += p.tally.elastic;
  e.externalWork = state_.externalWork;
  e.initial = state_.initialEnergy;
  e.friction = state_.friction;
  e.damping = state_.damping;
  e.retiredKinetic = state_.retiredKinetic;
  e.projection = state_.projection;
  return e;
}

double World::maxPenetration() const {
  double d = 0.0;
  for (const PairContacts& p : pairs_) d = std::max(d, p.maxDepth);
  return d;
}

void World::checkStability() {
  const auto where = [&](std::size_t i) {
    return format("t = %.6g s (step ", state_.time) + std::to_string(state_.steps) + "), body '" + state_.bodies.name[i] + "'";
  };
  for (std::size_t i = 0; i < state_.bodies.size(); ++i) {
    if (!state_.bodies.moves(i)) continue;
    if (!state_.bodies.position[i].allFinite() || !state_.bodies.velocity[i].allFinite() || !state_.bodies.angularMomentum[i].allFinite())
      throw SolverInstability(where(i) + ": non-finite position or velocity; the time step " + format("%.3g s", dt_) +
                              " is probably too large (automatic: " + format("%.3g s)", automaticDt_));
  }
  const EnergyBudget e = energy();
  state_.mostSupplied = std::max(state_.mostSupplied, e.initial + std::abs(e.gravityWork) + std::abs(e.externalWork));
  // The obstacles' work is booked a step late (the last evaluation's reaction over this step's
  // travel), so a body struck in this step has gained kinetic energy whose work is not booked yet:
  // at most one step's work at the reaction now (an indenter starting in contact with a node).
  double unbooked = 0.0;
  for (std::size_t k = 0; k < state_.spheres.size(); ++k)
    unbooked += std::abs(state_.sphereReaction[k].dot(state_.spheres[k].velocity)) * dt_;
  const double supplied = state_.mostSupplied + unbooked + 1e-12;
  // Between bodies the bound is a fraction of the thinnest block; against the analytic indenter,
  // whose penalty contact legitimately sinks deep at high loads (P = pi k_n R d^2), its radius.
  // The cause named from the motion: a slab at rest (kinetic energy under 1e-3 of the energy
  // supplied) sank in because the penalty is too soft for its forces, not because of the step.
  const int sphereCount = static_cast<int>(state_.spheres.size());
  for (const PairContacts& p : pairs_) {
    const bool indenter = p.b < 0 && -1 - p.b < sphereCount;
    const double bound = indenter ? state_.spheres[-1 - p.b].radius : penetrationLimit_;
    if (!(p.maxDepth > bound)) continue;
    const std::string against = p.b >= 0 ? "body '" + state_.bodies.name[p.b] + "'" : indenter ? "the indenter" : "an obstacle";
    const std::string rule = indenter ? "the indenter's radius" : "solver.max_penetration";
    const std::string cause =
        e.kinetic < 1e-3 * supplied
            ? format("the slab was at rest (kinetic energy %.2g of the energy supplied): ", e.kinetic / supplied) +
                  "the contact stiffness k_n = E M / L is too soft for these forces; set [span] length and interfaces to the "
                  "assembly's (a shorter L or more interfaces M stiffen it), or raise solver.max_penetration if this depth "
                  "is acceptable"
            : "the time step " + format("%.3g s", dt_) + " or the loading rate is too large";
    throw SolverInstability(where(p.a) + ": penetration " + format("%.4g mm", p.maxDepth * 1e3) + " into " + against +
                            ", beyond the bound " + format("%.4g mm", bound * 1e3) + " (" + rule + "); " + cause);
  }
  if (e.kinetic > settings_.energyGrowthLimit * supplied) {
    std::size_t worst = 0;
    for (std::size_t i = 0; i < state_.bodies.size(); ++i)
      if (state_.bodies.moves(i) && state_.bodies.kineticEnergy(i) > state_.bodies.kineticEnergy(worst)) worst = i;
    throw SolverInstability(where(worst) + ": kinetic energy " + format("%.4g J", e.kinetic) + " exceeds " +
                            format("%.3g x the energy supplied (%.4g J)", settings_.energyGrowthLimit, supplied) +
                            "; the time step " + format("%.3g s", dt_) + " is probably too large (automatic: " +
                            format("%.3g s)", automaticDt_));
  }
}

}  // namespace tessera

#include "solver/world.h"

#include "solver/broad_phase.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace tessera {

struct World::ThreadArena {
  tbb::task_arena arena;
  explicit ThreadArena(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
};

namespace {

ShapeModel makeShapeModel(const Shape& shape, bool exactConvex) {
  ShapeModel m;
  m.nodes = makeNodeBins(shape.nodes);
  m.sdf = shape.sdf;
  if (exactConvex && shape.convex) m.planes = shape.convex->planes;
  for (const auto& x : shape.nodes.positions) m.radius = std::max(m.radius, x.norm());
  return m;
}

// An upper estimate of the fastest mode of a free body: every node of its surface in sticking
// contact with a body like itself moving the other way (the checkerboard mode of a packed
// assembly; Gershgorin's bound on the mass-normalised stiffness matrix doubles each body's own
// stiffness). Along and about each principal axis e_k, over all nodes (docs/physics.md, "Time step"):
//   K_k = k_n sum a (n.e_k)^2 + k_t sum a (1 - (n.e_k)^2)                        omega^2 = 2 K_k / m
//   G_k = k_n sum a ((e_k x r).n)^2 + k_t sum a (|e_k x r|^2 - ((e_k x r).n)^2)    omega^2 = 2 G_k / I_k
// (k_t counts only with friction; without it no tangential force acts.) Translation-rotation
// coupling is left out: the measured critical steps (bench/stability_map.cpp) bound what that costs.
double fastestMode(const Shape& shape, double mass, const Eigen::Vector3d& inertia, const ContactParameters& p) {
  const double kn = p.normalStiffness(), kt = p.friction > 0 ? p.tangentialStiffness() : 0.0;
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

World::World(const Bundle& bundle, const ContactParameters& parameters, const SolverSettings& settings)
    : parameters_(parameters), settings_(settings), arena_(std::make_unique<ThreadArena>(settings.threads)) {
  if (!(parameters.normalStiffness() > 0)) throw std::invalid_argument("contact stiffness E M / L must be positive");
  if (!(settings.density > 0)) throw std::invalid_argument("density must be positive");
  if (settings.localDamping < 0 || settings.localDamping >= 1)
    throw std::invalid_argument("local damping must lie in [0, 1)");
  for (const Shape& s : bundle.shapes) shapes_.push_back(makeShapeModel(s, settings.exactConvexLevelSets));
  bodies_ = makeRigidBodies(bundle, settings.density);

  double omega = 0.0, thinnest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const Shape& shape = bundle.shapes[bodies_.shape[i]];
    thinnest = std::min(thinnest, boundingBox(shape.mesh.vertices).sizes().minCoeff());
    if (!bodies_.fixed[i]) omega = std::max(omega, fastestMode(shape, bodies_.mass[i], bodies_.inertia[i], parameters));
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
  penetrationLimit_ = settings.maxPenetration > 0 ? settings.maxPenetration : 0.25 * thinnest;
  if (!(settings_.broadPhaseMargin > 0)) settings_.broadPhaseMargin = settings.broadPhaseMarginRatio * thinnest;

  const std::size_t n = bodies_.size();
  force_.assign(n, Eigen::Vector3d::Zero());
  torque_.assign(n, Eigen::Vector3d::Zero());
  contactForce_.assign(n, Eigen::Vector3d::Zero());
  contactTorque_.assign(n, Eigen::Vector3d::Zero());
  dampingForce_.assign(n, Eigen::Vector3d::Zero());
  dampingTorque_.assign(n, Eigen::Vector3d::Zero());
  startPosition_ = bodies_.position;
  retired_.assign(n, 0);
}

WorldState World::state() const {
  WorldState s;
  s.bodies = bodies_;
  s.retired = retired_;
  s.spheres = spheres_;
  s.planes = planes_;
  s.pairs = pairs_;
  s.builtPosition = builtPosition_;
  s.builtSphereCentre = builtSphereCentre_;
  s.builtOrientation = builtOrientation_;
  s.pairsValid = pairsValid_;
  s.force = force_;
  s.torque = torque_;
  s.contactForce = contactForce_;
  s.contactTorque = contactTorque_;
  s.sphereReaction = sphereReaction_;
  s.dampingForce = dampingForce_;
  s.dampingTorque = dampingTorque_;
  s.forcesValid = forcesValid_;
  s.startPosition = startPosition_;
  s.initialEnergy = initialEnergy_;
  s.obstacleWork = obstacleWork_;
  s.friction = friction_;
  s.damping = damping_;
  s.retiredKinetic = retiredKinetic_;
  s.projection = projection_;
  s.mostSupplied = mostSupplied_;
  s.time = time_;
  s.steps = steps_;
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
  const std::size_t n = bodies_.size();
  requireEach(s.bodies.position, n, false, "positions", finite);
  requireEach(s.bodies.orientation, n, false, "orientations", unit);
  requireEach(s.bodies.velocity, n, false, "velocities", finite);
  requireEach(s.bodies.angularMomentum, n, false, "angular momenta", finite);
  requireEach(s.bodies.fixed, n, false, "fixed flags", [](char) { return true; });
  requireEach(s.retired, n, false, "retired flags", [](char) { return true; });
  for (const auto* v : {&s.builtPosition, &s.force, &s.torque, &s.contactForce, &s.contactTorque, &s.dampingForce,
                        &s.dampingTorque, &s.startPosition})
    requireEach(*v, n, true, "per-body vectors", finite);
  requireEach(s.builtOrientation, n, true, "per-body orientations", unit);
  for (const SphereObstacle& sphere : s.spheres)
    if (!finite(sphere.center) || !finite(sphere.velocity) || !(sphere.radius > 0) || !std::isfinite(sphere.radius) ||
        !(sphere.stiffnessFactor > 0) || !std::isfinite(sphere.stiffnessFactor))
      throw std::invalid_argument("an indenter with a non-finite or non-positive value");
  requireEach(s.sphereReaction, s.spheres.size(), true, "indenter reactions", finite);
  requireEach(s.builtSphereCentre, s.spheres.size(), true, "indenter positions", finite);
  const int obstacles = static_cast<int>(s.spheres.size() + s.planes.size());
  for (const PairContacts& p : s.pairs) {
    if (p.a < 0 || p.a >= static_cast<int>(n) || p.b < -obstacles || p.b >= static_cast<int>(n) || p.a == p.b)
      throw std::invalid_argument("a contact pair (" + std::to_string(p.a) + ", " + std::to_string(p.b) + ") names no body");
    for (const NodeContact& c : p.contacts) {
      const int body = (c.key >> 31) == 0 ? p.a : p.b;
      const std::size_t nodes = body >= 0 ? shapes_[bodies_.shape[body]].nodes.position.size() : 0;
      if ((body >= 0 && (c.key & 0x7fffffffu) >= nodes) || !finite(c.spring) || !std::isfinite(c.energy) || !std::isfinite(c.area))
        throw std::invalid_argument("a contact names no node, or holds a non-finite value");
    }
    if (!finite(p.forceA) || !finite(p.torqueA) || !finite(p.forceB) || !finite(p.torqueB))
      throw std::invalid_argument("a contact pair holds a non-finite force");
  }
  for (double e : {s.initialEnergy, s.obstacleWork, s.friction, s.damping, s.retiredKinetic, s.projection, s.mostSupplied, s.time})
    if (!std::isfinite(e)) throw std::invalid_argument("an energy or the time is not finite");
  if (s.time < 0 || s.steps < 0) throw std::invalid_argument("a negative time or step count");
}

void World::restore(const WorldState& s) {
  checkState(s);
  bodies_ = s.bodies;
  retired_ = s.retired;
  spheres_ = s.spheres;
  planes_ = s.planes;
  pairs_ = s.pairs;
  for (PairContacts& p : pairs_) p.kind = pairKind(p.b, static_cast<int>(spheres_.size()));
  builtPosition_ = s.builtPosition;
  builtSphereCentre_ = s.builtSphereCentre;
  builtOrientation_ = s.builtOrientation;
  pairsValid_ = s.pairsValid;
  force_ = s.force;
  torque_ = s.torque;
  contactForce_ = s.contactForce;
  contactTorque_ = s.contactTorque;
  sphereReaction_ = s.sphereReaction;
  dampingForce_ = s.dampingForce;
  dampingTorque_ = s.dampingTorque;
  forcesValid_ = s.forcesValid;
  startPosition_ = s.startPosition;
  initialEnergy_ = s.initialEnergy;
  obstacleWork_ = s.obstacleWork;
  friction_ = s.friction;
  damping_ = s.damping;
  retiredKinetic_ = s.retiredKinetic;
  projection_ = s.projection;
  mostSupplied_ = s.mostSupplied;
  time_ = s.time;
  steps_ = s.steps;
}

void World::retireBody(int i) {
  if (retired_[i]) return;
  retiredKinetic_ += bodies_.kineticEnergy(i);
  retired_[i] = 1;
  bodies_.fixed[i] = 1;
  bodies_.velocity[i].setZero();
  bodies_.angularMomentum[i].setZero();
  pairsValid_ = forcesValid_ = false;
}

World::~World() = default;

Eigen::AlignedBox3d World::bodyBox(int i, double margin) const {
  return worldBox(shapes_[bodies_.shape[i]].nodes.box, bodies_.orientation[i], bodies_.position[i], margin);
}

double World::bodySize(int i) const { return shapes_[bodies_.shape[i]].nodes.box.sizes().minCoeff(); }

int World::addSphere(const SphereObstacle& sphere) {
  spheres_.push_back(sphere);
  sphereReaction_.push_back(Eigen::Vector3d::Zero());
  pairsValid_ = forcesValid_ = false;
  return static_cast<int>(spheres_.size()) - 1;
}

int World::addPlane(const PlaneObstacle& plane) {
  planes_.push_back(plane);
  planes_.back().normal.normalize();
  pairsValid_ = forcesValid_ = false;
  return static_cast<int>(planes_.size()) - 1;
}

// Candidate pairs from boxes enlarged by the margin m, rebuilt only when a body (or sphere) has
// moved or turned (angle x radius) by more than 0.4 m since the last build; contact states carry
// over by pair key. Between builds any two bodies move by at most 0.8 m relative to each other, so
// a node more than candidateBand() = 1.25 m outside the other side when the pair's node
// candidates are built (in its next evaluation) cannot touch it before the next build, even where
// the grid's level set is 1.5-Lipschitz rather than 1.
double World::candidateBand() const { return 1.25 * settings_.broadPhaseMargin; }

void World::updatePairs() {
  const double margin = settings_.broadPhaseMargin;
  if (pairsValid_) {
    bool moved = false;
    for (std::size_t i = 0; i < bodies_.size() && !moved; ++i) {
      if (bodies_.fixed[i]) continue;
      const double turn = bodies_.orientation[i].angularDistance(builtOrientation_[i]) * shapes_[bodies_.shape[i]].radius;
      moved = (bodies_.position[i] - builtPosition_[i]).norm() + turn > 0.4 * margin;
    }
    for (std::size_t k = 0; k < spheres_.size() && !moved; ++k)
      moved = (spheres_[k].center - builtSphereCentre_[k]).norm() > 0.4 * margin;
    if (!moved) return;
  }

  std::vector<Eigen::AlignedBox3d> boxes;
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    boxes.push_back(retired_[i] ? Eigen::AlignedBox3d()  // empty: intersects nothing
                                : worldBox(shapes_[bodies_.shape[i]].nodes.box, bodies_.orientation[i], bodies_.position[i], margin));
  std::vector<std::pair<int, int>> wanted = sweepPairs(boxes, bodies_.fixed);
  const int sphereCount = static_cast<int>(spheres_.size());
  for (int k = 0; k < sphereCount; ++k) {
    const Eigen::AlignedBox3d box(spheres_[k].center.array() - spheres_[k].radius - margin,
                                  spheres_[k].center.array() + spheres_[k].radius + margin);
    for (int i = 0; i < static_cast<int>(bodies_.size()); ++i)
      if (boxes[i].intersects(box)) wanted.emplace_back(i, -1 - k);
  }
  for (int k = 0; k < static_cast<int>(planes_.size()); ++k)
    for (int i = 0; i < static_cast<int>(bodies_.size()); ++i)
      if (!bodies_.fixed[i] && !retired_[i]) wanted.emplace_back(i, -1 - sphereCount - k);
  std::sort(wanted.begin(), wanted.end());

  // Keep the state of pairs that stay candidates (both lists sorted by (a, b)).
  std::vector<PairContacts> next;
  next.reserve(wanted.size());
  std::sort(pairs_.begin(), pairs_.end(), [](const PairContacts& x, const PairContacts& y) {
    return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
  });
  std::size_t old = 0;
  for (const auto& [a, b] : wanted) {
    while (old < pairs_.size() && std::make_pair(pairs_[old].a, pairs_[old].b) < std::make_pair(a, b)) ++old;
    if (old < pairs_.size() && pairs_[old].a == a && pairs_[old].b == b) {
      next.push_back(std::move(pairs_[old]));
    } else {
      PairContacts pair;
      pair.a = a;
      pair.b = b;
      pair.kind = pairKind(b, sphereCount);
      next.push_back(std::move(pair));
    }
  }
  pairs_ = std::move(next);
  for (PairContacts& pair : pairs_) pair.candidatesValid = false;
  builtPosition_ = bodies_.position;
  builtOrientation_ = bodies_.orientation;
  builtSphereCentre_.clear();
  for (const auto& s : spheres_) builtSphereCentre_.push_back(s.center);
  pairsValid_ = true;
}

void World::evaluateForces() {
  updatePairs();
  ContactScene scene{&bodies_, &shapes_, &spheres_, &planes_, parameters_,
                     parameters_.normalStiffness(), parameters_.tangentialStiffness(), dt_, candidateBand()};
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs_.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t p = r.begin(); p != r.end(); ++p) evaluatePair(scene, pairs_[p]);
    });
  });

  // Reduce per body in pair order: the same sums in the same order for any thread count.
  std::fill(contactForce_.begin(), contactForce_.end(), Eigen::Vector3d::Zero());
  std::fill(contactTorque_.begin(), contactTorque_.end(), Eigen::Vector3d::Zero());
  std::fill(sphereReaction_.begin(), sphereReaction_.end(), Eigen::Vector3d::Zero());
  for (const PairContacts& pair : pairs_) {
    friction_ += pair.tally.friction;
    damping_ += pair.tally.viscous;
    projection_ += pair.tally.projection;
    contactForce_[pair.a] += pair.forceA;
    contactTorque_[pair.a] += pair.torqueA;
    switch (pair.kind) {
      case PairKind::Bodies:
        contactForce_[pair.b] += pair.forceB;
        contactTorque_[pair.b] += pair.torqueB;
        break;
      case PairKind::Sphere: sphereReaction_[-1 - pair.b] += pair.forceB; break;
      case PairKind::Plane: break;  // fixed: its reaction is not needed
    }
  }

  // Gravity and damping (docs/physics.md, "Damping").
  const double alpha = settings_.localDamping, c = settings_.viscousDamping;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const Eigen::Vector3d f = contactForce_[i] + bodies_.mass[i] * settings_.gravity;
    const Eigen::Vector3d& t = contactTorque_[i];
    Eigen::Vector3d fd = Eigen::Vector3d::Zero(), td = Eigen::Vector3d::Zero();
    if (!bodies_.fixed[i]) {
      const Eigen::Vector3d v = bodies_.velocity[i], w = bodies_.angularVelocity(i);
      if (c > 0) {
        fd -= c * bodies_.mass[i] * v;
        td -= c * (bodies_.orientation[i] * bodies_.angularMomentum[i]);  // c I omega = c L
      }
      if (alpha > 0)
        for (int k = 0; k < 3; ++k) {
          fd[k] -= alpha * std::abs(f[k] + fd[k]) * (v[k] > 0 ? 1.0 : v[k] < 0 ? -1.0 : 0.0);
          td[k] -= alpha * std::abs(t[k] + td[k]) * (w[k] > 0 ? 1.0 : w[k] < 0 ? -1.0 : 0.0);
        }
    }
    dampingForce_[i] = fd;
    dampingTorque_[i] = td;
    force_[i] = f + fd;
    torque_[i] = t + td;
  }
  forcesValid_ = true;
}

// Velocity Verlet (kick-drift-kick) for translation; the rotation drift is the free-rotor
// splitting of rotateFreely, with torque kicks in the body frame on either side (docs/physics.md).
void World::step() {
  if (!forcesValid_) {
    evaluateForces();
    if (steps_ == 0) {
      const EnergyBudget e = energy();
      initialEnergy_ = e.kinetic + e.elastic;
    }
  }
  const double h = 0.5 * dt_;
  // A half kick of body i; the damping forces' work over it, exactly as the kick changes the
  // kinetic energy: h f . (v_before + v_after) / 2 (and h tau . omega_mean for the rotation).
  const auto kick = [&](std::size_t i) {
    const Eigen::Vector3d v0 = bodies_.velocity[i], L0 = bodies_.angularMomentum[i];
    bodies_.velocity[i] += h * force_[i] / bodies_.mass[i];
    bodies_.angularMomentum[i] += h * (bodies_.orientation[i].conjugate() * torque_[i]);
    if (dampingForce_[i].isZero() && dampingTorque_[i].isZero()) return;
    const Eigen::Vector3d omega = bodies_.orientation[i] * (0.5 * (L0 + bodies_.angularMomentum[i])).cwiseQuotient(bodies_.inertia[i]);
    damping_ -= h * (dampingForce_[i].dot(0.5 * (v0 + bodies_.velocity[i])) + dampingTorque_[i].dot(omega));
  };
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.fixed[i]) continue;
    kick(i);
    bodies_.position[i] += dt_ * bodies_.velocity[i];
    rotateFreely(bodies_.orientation[i], bodies_.angularMomentum[i], bodies_.inertia[i], dt_);
  }
  for (std::size_t k = 0; k < spheres_.size(); ++k) {
    // Work of the prescribed motion on the bodies over this step (reaction from the last evaluation).
    obstacleWork_ += -sphereReaction_[k].dot(spheres_[k].velocity) * dt_;
    spheres_[k].center += dt_ * spheres_[k].velocity;
  }
  evaluateForces();
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (!bodies_.fixed[i]) kick(i);
  time_ += dt_;
  ++steps_;
  checkStability();
}

EnergyBudget World::energy() const {
  EnergyBudget e;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    // Every body: a retired one keeps the gravity work done on it until it was frozen.
    e.gravityWork += bodies_.mass[i] * settings_.gravity.dot(bodies_.position[i] - startPosition_[i]);
    if (!bodies_.fixed[i]) e.kinetic += bodies_.kineticEnergy(i);
  }
  for (const PairContacts& p : pairs_) e.elastic += p.tally.elastic;
  e.obstacleWork = obstacleWork_;
  e.initial = initialEnergy_;
  e.friction = friction_;
  e.damping = damping_;
  e.retiredKinetic = retiredKinetic_;
  e.projection = projection_;
  return e;
}

double World::maxPenetration() const {
  double d = 0.0;
  for (const PairContacts& p : pairs_) d = std::max(d, p.maxDepth);
  return d;
}

void World::checkStability() {
  const auto where = [&](std::size_t i) {
    return format("t = %.6g s (step ", time_) + std::to_string(steps_) + "), body '" + bodies_.name[i] + "'";
  };
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.fixed[i]) continue;
    if (!bodies_.position[i].allFinite() || !bodies_.velocity[i].allFinite() || !bodies_.angularMomentum[i].allFinite())
      throw SolverInstability(where(i) + ": non-finite position or velocity; the time step " + format("%.3g s", dt_) +
                              " is probably too large (automatic: " + format("%.3g s)", automaticDt_));
  }
  // Between bodies the bound is a fraction of the thinnest block; against the analytic indenter,
  // whose penalty contact legitimately sinks deep at high loads (P = pi k_n R d^2), its radius.
  const int sphereCount = static_cast<int>(spheres_.size());
  for (const PairContacts& p : pairs_)
    if (p.maxDepth > (p.b < 0 && -1 - p.b < sphereCount ? spheres_[-1 - p.b].radius : penetrationLimit_))
      throw SolverInstability(where(p.a) + ": penetration " + format("%.4g mm", p.maxDepth * 1e3) + " beyond the bound (" +
                              format("%.4g mm", penetrationLimit_ * 1e3) + ", the indenter's radius against it; against " +
                              (p.b >= 0 ? "body '" + bodies_.name[p.b] + "'" : std::string("an obstacle")) +
                              "); the time step " + format("%.3g s", dt_) + " or the loading rate is too large");
  const EnergyBudget e = energy();
  mostSupplied_ = std::max(mostSupplied_, e.initial + std::abs(e.gravityWork) + std::abs(e.obstacleWork));
  const double supplied = mostSupplied_ + 1e-12;
  if (e.kinetic > settings_.energyGrowthLimit * supplied) {
    std::size_t worst = 0;
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      if (!bodies_.fixed[i] && bodies_.kineticEnergy(i) > bodies_.kineticEnergy(worst)) worst = i;
    throw SolverInstability(where(worst) + ": kinetic energy " + format("%.4g J", e.kinetic) + " exceeds " +
                            format("%.3g x the energy supplied (%.4g J)", settings_.energyGrowthLimit, supplied) +
                            "; the time step " + format("%.3g s", dt_) + " is probably too large (automatic: " +
                            format("%.3g s)", automaticDt_));
  }
}

}  // namespace tessera

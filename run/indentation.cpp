#include "run/indentation.h"

#include "run/assembly_state.h"
#include "run/load_point.h"
#include "run/loading_rate.h"
#include "run/protocol_scale.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace tessera {

void setEnergies(CurveSample& s, const EnergyBudget& e) {
  s.kinetic = e.kinetic;
  s.externalWork = e.externalWork;
  s.elastic = e.elastic;
  s.friction = e.friction;
  s.damping = e.damping;
  s.gravityWork = e.gravityWork;
  s.retiredKinetic = e.retiredKinetic;
  s.projection = e.projection;
  s.residual = e.residual();
}

namespace {

Snapshot snapshotOf(const World& world, int sphere, double delta, double load) {
  Snapshot s{delta, load, world.bodies().position, world.bodies().orientation, {}, world.bodies().velocity,
             world.sphere(sphere).center};
  for (int k = 0; k < world.pairCount(); ++k) {
    const PairView p = world.pair(k);
    if (p.nodeContacts > 0)
      s.forces.push_back({p.a, p.b, p.point, p.force, p.normalForce, p.nodeContacts, p.area, p.slidingNodes, p.normalStiffness});
  }
  return s;
}

// After settling: choose the target, measure its thickness, place the indenter just above its top.
void startLoading(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                  IndentationState& state) {
  const RigidBodies& bodies = world.bodies();
  const LoadPoint load = chooseLoadPoint(bundle, scene.indenter);
  record.target = load.body;
  const Eigen::Vector2d at = bodies.position[record.target].head<2>() + load.offset;
  record.targetName = bodies.name[record.target];
  // h: the settled block's extent along the loading direction (z) through the load point.
  const TriangleMesh& mesh = bundle.shapes[bodies.shape[record.target]].mesh;
  const double top = heightRange(mesh, bodies.orientation[record.target], bodies.position[record.target]).second;
  record.thickness = loadedThickness(mesh, bodies.orientation[record.target], bodies.position[record.target], at);
  record.deltaMax = scene.protocol.deltaMax > 0 ? scene.protocol.deltaMax : scene.protocol.deltaMaxRatio * record.thickness;
  SphereObstacle indenter;
  indenter.radius = scene.indenter.radius > 0 ? scene.indenter.radius : scene.indenter.radiusRatio * record.thickness;
  // With the adaptive loading rate, the indenter starts at its slowest speed and speeds up while
  // the slab follows quasi-statically.
  const double speed = indenterSpeed(world, scene.indenter, record.thickness);
  indenter.velocity = Eigen::Vector3d(0, 0, -(scene.protocol.quasiStaticTarget > 0 ? kSlowestSpeedFraction * speed : speed));
  // Above the block's top by its radius, but never more than 5 % of h above its first contact
  // with the block's surface nodes there: on a tilted block the top is far above that contact (a
  // dome's indenter travelled 23 mm to it), on a flat one it is the top (an approach of r^2 / 2R).
  const std::optional<double> touch =
      sphereTouchHeight(bundle.shapes[bodies.shape[record.target]].nodes, bodies.orientation[record.target],
                        bodies.position[record.target], at, indenter.radius);
  const double start = std::min(top + indenter.radius, touch ? *touch + 0.05 * record.thickness : INFINITY);
  indenter.center = Eigen::Vector3d(at.x(), at.y(), start + scene.indenter.clearance);
  indenter.stiffnessFactor = scene.indenter.stiffnessFactor;
  state.sphere = world.addSphere(indenter);
  state.settledPosition = bodies.position;
  state.outAt.assign(bodies.size(), -1.0);
  state.loadStart = world.time();
  state.speedSince = state.loadStart;
  state.phase = 1;
}

// At a sample: who is held, who has fallen (and since when), who has left and is retired.
// Returns, for each body, whether it is out (listed in record.fallen).
std::vector<char> updateFallen(World& world, const Scene& scene, IndentationRecord& record, IndentationState& state,
                               double delta) {
  const FallenRule rule{scene.protocol.fallenClearance};
  const std::vector<char> supported = supportedBodies(world), touching = touchingBlocks(world),
                          pushed = pushedThroughBodies(world, state.settledPosition);
  const RigidBodies& bodies = world.bodies();
  std::vector<char> out(bodies.size(), 0);
  record.fallen.clear();
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    if (world.isSupport(i)) continue;
    if (world.isRetired(i)) {
      record.fallen.push_back({bodies.name[i], state.outAt[i], true, false});
      out[i] = 1;
      continue;
    }
    const bool through = pushed[i];
    if (supported[i] && !through) state.outAt[i] = -1.0;
    else if (state.outAt[i] < 0) state.outAt[i] = delta;
    if (canRetire(world, i, touching, supported, state.settledPosition[i], rule)) {
      world.retireBody(i);
      record.fallen.push_back({bodies.name[i], state.outAt[i], true, false});
      out[i] = 1;
    } else if (through || hasFallen(world, i, supported, state.settledPosition[i], rule)) {
      record.fallen.push_back({bodies.name[i], state.outAt[i], false, through});
      out[i] = 1;
    }
  }
  return out;
}

}  // namespace

void recordStepping(IndentationRecord& record, const World& world) {
  record.steps = world.stepCount();
  record.timeStep = world.timeStep();
  record.implicit = world.settings().method == SolverMethod::Implicit;
  record.implicitCounts = world.implicitCounts();
}

namespace {

// The indenter's penetration, as a fraction of its radius, past which a run warns (checkIndenterDepth).
constexpr double kDeepIndenterRatio = 0.5;

// One call of runIndentation: its wall clock, progress reports and checkpoints, and the settling
// and loading phases as steps of the protocol (docs/physics.md, "Protocol").
class IndentationRun {
public:
  IndentationRun(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                 IndentationState& state, const RunHooks& hooks)
      : world_(world), bundle_(bundle), scene_(scene), record_(record), state_(state), hooks_(hooks),
        start_(Clock::now()), wallBefore_(record.wallSeconds), stepsBefore_(world.stepCount()) {
    record_.timeStep = world_.timeStep();
    record_.settleKinetic = settleThreshold(world_, scene_.protocol);
    record_.settleMaxTime = settleTimeLimit(world_, scene_.protocol);
  }

  void run() {
    if (state_.phase == 0 && !settle()) return finish();
    if (state_.phase == 0) {
      endSettling();
      startLoading(world_, bundle_, scene_, record_, state_);
    }
    load();
    finish();
  }

private:
  using Clock = std::chrono::steady_clock;

  double wall() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  // ETA: the steps left at this session's rate.
  double eta(double travelLeft, double speed) const {
    return travelLeft / world_.travelPerStep(speed) / std::max(sessionRate(), 1e-9);
  }
  double sessionRate() const { return (world_.stepCount() - stepsBefore_) / std::max(wall(), 1e-9); }
  bool progressDue() {
    if (!hooks_.progress || wall() - lastProgress_ < scene_.output.progressSeconds) return false;
    lastProgress_ = wall();
    return true;
  }
  bool interrupted() {
    if (!hooks_.interrupted || !hooks_.interrupted()) return false;
    record_.stopReason = StopReason::Interrupted;
    return true;
  }
  // The record brought up to now and handed to the checkpoint hook: at the session's end, and
  // every checkpointSeconds of wall time (on a step that is a multiple of 100).
  void finish() {
    recordStepping(record_, world_);
    record_.wallSeconds = wallBefore_ + wall();
    if (hooks_.checkpoint) hooks_.checkpoint(state_);
  }
  void checkpointDue() {
    if (!hooks_.checkpoint || world_.stepCount() % 100 != 0 || wall() - lastCheckpoint_ < hooks_.checkpointSeconds) return;
    lastCheckpoint_ = wall();
    finish();
  }

  // 1. Settle under gravity, until at rest or the settling time limit. False when interrupted.
  bool settle() {
    while (state_.phase == 0) {
      if (interrupted()) return false;
      if (world_.time() >= record_.settleMaxTime) break;
      world_.step();
      // Explicit: checked every 100 steps from the 1000th (damped dynamics first has to start
      // moving); implicit: each increment is a balance of forces, from the second on.
      const bool implicit = world_.settings().method == SolverMethod::Implicit;
      const bool due = implicit ? world_.stepCount() >= 2 : world_.stepCount() % 100 == 0 && world_.stepCount() >= 1000;
      if (due && world_.energy().kinetic < record_.settleKinetic) {
        record_.settled = true;
        break;
      }
      if (progressDue()) reportSettling();
      checkpointDue();
    }
    return true;
  }

  // While settling the ETA takes the loading's steps from the would-be target's size (settling's
  // own end is not known beforehand), and the settling's steps left to its limit at the simulated
  // time a step has taken so far.
  void reportSettling() {
    const int target = centralFreeBody(bundle_);
    const double h = target >= 0 ? world_.bodySize(target) : 0.0;
    const double travel =
        scene_.indenter.clearance + (scene_.protocol.deltaMax > 0 ? scene_.protocol.deltaMax : scene_.protocol.deltaMaxRatio * h);
    const EnergyBudget e = world_.energy();
    const double settleStepsLeft =
        (record_.settleMaxTime - world_.time()) * world_.stepCount() / std::max(world_.time(), 1e-300);
    hooks_.progress({0.0, 0.0, e.kinetic, e.externalWork, 0, world_.stepCount(), world_.stepCount() / (wallBefore_ + wall()),
                     eta(travel, indenterSpeed(world_, scene_.indenter, h)), true,
                     std::max(0.0, settleStepsLeft) / std::max(sessionRate(), 1e-9)});
  }

  // The settled state recorded; an assembly that does not stand under its own weight (supports,
  // friction) is not a test, and is named so.
  void endSettling() {
    record_.settleTime = world_.time();
    record_.settleSteps = world_.stepCount();
    const RigidBodies& b = world_.bodies();
    const std::vector<Eigen::Vector3d>& built = world_.startPositions();
    for (int i = 0; i < static_cast<int>(b.size()); ++i)
      if (b.moves(i) && built[i].z() - b.position[i].z() > scene_.protocol.fallenClearance * world_.bodySize(i))
        ++record_.sunkWhileSettling;
    if (record_.sunkWhileSettling > 0 && hooks_.warning)
      hooks_.warning(std::to_string(record_.sunkWhileSettling) + " free bodies sank by more than " +
                     std::to_string(scene_.protocol.fallenClearance).substr(0, 4) +
                     " of their size while settling: the assembly does not stand under its own weight with these "
                     "supports and this friction; check the fixed bodies and material.friction");
  }

  // A curve sample at the state now; out_ gets the bodies out.
  void sample(double delta, double load) {
    out_ = updateFallen(world_, scene_, record_, state_, delta);
    const ContactCounts c = countContacts(world_, record_.target);
    CurveSample s;
    s.time = world_.time() - state_.loadStart;
    s.delta = delta;
    s.load = load;
    s.blockDisplacement = state_.settledPosition[record_.target].z() - world_.bodies().position[record_.target].z();
    s.indenterPenetration = c.indenterDepth;
    s.contacts = static_cast<double>(c.all);
    s.blockContacts = static_cast<double>(c.blocks);
    s.slidingContacts = static_cast<double>(c.blocksSliding);
    s.loadedContacts = static_cast<double>(c.loaded);
    s.loadedSliding = static_cast<double>(c.loadedSliding);
    setEnergies(s, world_.energy());
    s.indenterSpeed = -world_.sphere(state_.sphere).velocity.z();
    record_.curve.push_back(s);
  }

  // Quasi-static check while loading up to the peak (past the first 5 % of h of contact): warned once.
  void checkQuasiStatic(double delta, double load) {
    const CurveSample& last = record_.curve.back();
    if (warnedQuasiStatic_ || load < state_.peak || delta <= 0.05 * record_.thickness || !(last.externalWork > 0) ||
        last.kinetic <= scene_.protocol.quasiStaticLimit * last.externalWork)
      return;
    warnedQuasiStatic_ = true;
    if (hooks_.warning)
      hooks_.warning("loading too fast: kinetic energy " + std::to_string(last.kinetic / last.externalWork).substr(0, 6) +
                     " x the indenter's work at delta = " + std::to_string(delta * 1e3).substr(0, 5) +
                     " mm (limit protocol.quasi_static_limit); lower indenter.speed or indenter.speed_ratio");
  }

  // The indenter sunk past half its radius into the bodies: its penalty contact far outside the
  // small overlaps it stands for (P = pi k_n R d^2 on a face; on a ridge or an edge it sinks much
  // deeper), and the reaction it reports no longer the slab's resistance (wedged between blocks,
  // it can even be pulled down). Warned once. The paper's studies stay below 0.4 R; an indenter
  // of 2.5 mm on a 13.5 mm tetrahedral block's ridge reached 0.95 R.
  void checkIndenterDepth(double delta) {
    const CurveSample& last = record_.curve.back();
    if (warnedDeep_ || !(last.indenterPenetration > kDeepIndenterRatio * record_.indenterRadius)) return;
    warnedDeep_ = true;
    if (hooks_.warning)
      hooks_.warning("the indenter has sunk " + std::to_string(last.indenterPenetration * 1e3).substr(0, 5) + " mm (" +
                     std::to_string(last.indenterPenetration / record_.indenterRadius).substr(0, 4) + " of its radius) into the bodies at delta = " +
                     std::to_string(delta * 1e3).substr(0, 5) +
                     " mm: its reaction is no longer the slab's; give a larger indenter.radius (or radius_ratio) or indenter.stiffness_factor");
  }

  // The indenter's speed after a sample: as the sample hook sets it, or the adaptive loading rate
  // (docs/physics.md, "Adaptive loading rate"). Returns whether the hook asked to stop.
  bool steer(double velocity, double travel, double path, double load) {
    IndentationControl control{velocity, false};
    bool requested = false;
    if (hooks_.sample) {
      hooks_.sample(record_.curve.back(), control);
      requested = control.stop;
    }
    const bool steered = control.indenterSpeed != velocity;
    if (steered && world_.settings().method == SolverMethod::Explicit) {  // implicit increments follow any speed
      // The broad phase finds the indenter's contacts only if it moves less than its margin
      // between rebuilds: at most a tenth of the margin per step.
      const double fastest = 0.1 * world_.settings().broadPhaseMargin / world_.timeStep();
      if (!std::isfinite(control.indenterSpeed) || std::abs(control.indenterSpeed) > fastest) {
        record_.stopReason = StopReason::Interrupted;  // as stopped here: resumable, its checkpoint written
        finish();
        throw std::invalid_argument("the sample hook set the indenter speed to " + std::to_string(control.indenterSpeed) +
                                    " m/s; it must be finite and at most " + std::to_string(fastest) +
                                    " m/s (a tenth of the broad-phase margin per time step)");
      }
    }
    // Adaptive loading rate, from first contact until the load first falls below half its largest
    // value (past the peak), or a sample hook sets the speed (it steers from then on): the speed
    // that keeps KE / W under the target.
    const double target = scene_.protocol.quasiStaticTarget;
    if (target > 0 && (steered || (state_.peak > 0 && load < 0.5 * state_.peak))) state_.rateAdapted = true;
    const CurveSample& last = record_.curve.back();
    if (target > 0 && !state_.rateAdapted && last.externalWork > 0 && velocity > 0) {
      double recent = 0;
      const std::size_t n = record_.curve.size();
      for (std::size_t i = n - std::min<std::size_t>(n, kRecentSamples); i < n; ++i)
        if (record_.curve[i].externalWork > 0)
          recent = std::max(recent, record_.curve[i].kinetic / record_.curve[i].externalWork);
      control.indenterSpeed = adaptedIndenterSpeed(velocity, last.kinetic / last.externalWork, recent, target,
                                                   kSlowestSpeedFraction * speed_, speed_);
    }
    if (control.indenterSpeed != velocity) {
      state_.travelBase = travel;
      state_.pathBase = path;
      state_.speedSince = world_.time();
      world_.sphere(state_.sphere).velocity = Eigen::Vector3d(0, 0, -control.indenterSpeed);
    }
    return requested;
  }

  // 2. Push at constant speed (or as the sample hook steers the indenter), to delta_max, the
  // failure or a stop the hook asks for.
  void load() {
    speed_ = indenterSpeed(world_, scene_.indenter, record_.thickness);  // the protocol's
    record_.indenterSpeed = speed_;
    record_.indenterRadius = world_.sphere(state_.sphere).radius;
    const double travelMax = record_.deltaMax + scene_.indenter.clearance + record_.indenterRadius;
    // The deepest delta sampled so far (from the curve, so a resumed run knows it): the loading
    // envelope, where failure is read (run/response.cpp).
    double deepest = 0.0;
    for (const CurveSample& c : record_.curve) deepest = std::max(deepest, c.delta);
    while (state_.phase == 1) {
      if (interrupted()) return;
      world_.step();
      // Travel (down) and path since loading began; with the protocol's constant speed both are speed x t.
      const double velocity = -world_.sphere(state_.sphere).velocity.z();
      const double travel = state_.travelBase + velocity * (world_.time() - state_.speedSince);
      const double path = state_.pathBase + std::abs(velocity) * (world_.time() - state_.speedSince);
      const double load = world_.sphereReaction(state_.sphere).z();
      if (state_.contactTravel < 0 && load > 0) {
        // First contact was made within the last step, when the first node met the indenter: as far
        // back as that node has gone into it plus what the loaded block has moved down since. It
        // matters for the implicit method's increments (10 um; an explicit step moves 0.04 um).
        const double sunk = state_.settledPosition[record_.target].z() - world_.bodies().position[record_.target].z();
        const double past = countContacts(world_, record_.target).indenterDepth + std::max(sunk, 0.0);
        state_.contactTravel = travel - past;
        state_.contactPath = path - past;
      }
      const double delta = state_.contactTravel < 0 ? 0.0 : travel - state_.contactTravel;
      const double along = state_.contactTravel < 0 ? 0.0 : path - state_.contactPath;  // = delta while only going down
      state_.peak = std::max(state_.peak, load);

      // A sample every sampleEvery of path, and, when the indenter goes slower than half the
      // protocol's speed (a hold), every 2 sampleEvery / speed of time: the sample hook keeps hearing.
      // With the adaptive loading rate, a hold is slower than half its slowest speed.
      bool sampled = false, requested = false;
      const bool pathDue = along >= state_.nextSample;
      const bool hold = scene_.protocol.quasiStaticTarget <= 0 || std::abs(velocity) < 0.5 * kSlowestSpeedFraction * speed_;
      const bool timeDue = hold && !record_.curve.empty() &&
                           world_.time() - state_.loadStart - record_.curve.back().time >= 2 * scene_.output.sampleEvery / speed_;
      if (state_.contactTravel >= 0 && (pathDue || timeDue)) {
        sample(delta, load);
        sampled = true;
        checkQuasiStatic(delta, load);
        checkIndenterDepth(delta);
        state_.nextSample = pathDue ? state_.nextSample + scene_.output.sampleEvery : along + scene_.output.sampleEvery;
        // The load gone: below 1 % of the peak since quietFrom, on the loading envelope (a steered
        // indenter backing off unloads the slab; that is no failure to stop on).
        const bool onEnvelope = delta >= deepest;
        deepest = std::max(deepest, delta);
        if (state_.peak > 0 && load < 0.01 * state_.peak && onEnvelope) {
          if (state_.quietFrom < 0) state_.quietFrom = along;
        } else {
          state_.quietFrom = -1;
        }
        requested = steer(velocity, travel, path, load);
      }
      if (state_.contactTravel >= 0 && along >= state_.nextSnapshot) {
        record_.snapshots.push_back(snapshotOf(world_, state_.sphere, delta, load));
        state_.nextSnapshot += scene_.output.snapshotEvery;
      }
      if (progressDue()) {
        // Travel left: to first contact (the clearance) and on to delta_max.
        const double left = state_.contactTravel < 0 ? scene_.indenter.clearance - travel + record_.deltaMax
                                                     : record_.deltaMax - delta;
        const EnergyBudget e = world_.energy();
        hooks_.progress({delta, load, e.kinetic, e.externalWork, static_cast<long>(countContacts(world_, record_.target).all),
                         world_.stepCount(), world_.stepCount() / (wallBefore_ + wall()),
                         eta(std::max(left, 0.0), velocity > 0 ? velocity : speed_), false, 0.0});
      }
      const bool reachedMax = (state_.contactTravel >= 0 && delta >= record_.deltaMax) ||
                              travel > travelMax + record_.deltaMax;  // the latter: never touched anything
      const bool failed = scene_.protocol.stopOnFailure && sampled && state_.quietFrom >= 0 &&
                          along - state_.quietFrom >= scene_.protocol.quietTravel * record_.thickness &&
                          restingBodies(world_, out_, scene_.protocol.restSpeedRatio * speed_);
      if (reachedMax || failed || requested) return stop(requested ? StopReason::Requested : failed ? StopReason::Failure : StopReason::DeltaMax, delta, load);
      checkpointDue();
    }
  }

  // The state at the stop closes the curve and the snapshots.
  void stop(StopReason reason, double delta, double load) {
    record_.stopReason = reason;
    if (state_.contactTravel >= 0 && (record_.curve.empty() || record_.curve.back().time < world_.time() - state_.loadStart))
      sample(delta, load);
    if (!record_.curve.empty() && (record_.snapshots.empty() || record_.snapshots.back().delta != record_.curve.back().delta))
      record_.snapshots.push_back(snapshotOf(world_, state_.sphere, delta, load));
    state_.phase = 2;
  }

  World& world_;
  const Bundle& bundle_;
  const Scene& scene_;
  IndentationRecord& record_;
  IndentationState& state_;
  const RunHooks& hooks_;
  const Clock::time_point start_;
  const double wallBefore_;
  const long stepsBefore_;
  double lastProgress_ = 0.0, lastCheckpoint_ = 0.0;
  double speed_ = 0.0;             ///< m/s, the protocol's indenter speed
  bool warnedQuasiStatic_ = false;
  bool warnedDeep_ = false;
  std::vector<char> out_;          ///< bodies out at the last sample
};

}  // namespace

void runIndentation(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                    IndentationState& state, const RunHooks& hooks) {
  IndentationRun(world, bundle, scene, record, state, hooks).run();
}

}  // namespace tessera

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

namespace {

Snapshot snapshotOf(const World& world, int sphere, double delta, double load) {
  Snapshot s{delta, load, world.bodies().position, world.bodies().orientation, {}, world.bodies().velocity,
             world.sphere(sphere).center};
  for (const PairContacts& p : world.pairs()) {
    if (p.contacts.empty()) continue;
    double area = 0;
    for (const NodeContact& c : p.contacts) area += c.area;
    s.forces.push_back({p.a, p.b, p.forcePoint, p.forceA, p.normalForceA, static_cast<int>(p.contacts.size()), area,
                        p.tally.sliding});
  }
  return s;
}

// After settling: choose the target, measure its thickness, place the indenter just above its top.
void startLoading(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                  IndentationState& state) {
  RigidBodies& bodies = world.bodies();
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

void runIndentation(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                    IndentationState& state, const RunHooks& hooks) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double wallBefore = record.wallSeconds;
  const auto wall = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  record.timeStep = world.timeStep();
  record.settleKinetic = settleThreshold(world, scene.protocol);
  record.settleMaxTime = settleTimeLimit(world, scene.protocol);
  const long stepsBefore = world.stepCount();
  double lastProgress = wall(), lastCheckpoint = wall();
  // ETA: the steps left at this session's rate. While settling, the loading's steps from the
  // would-be target's size (settling's own end is not known beforehand).
  const auto eta = [&](double travelLeft, double speed) {
    const double rate = (world.stepCount() - stepsBefore) / std::max(wall(), 1e-9);
    return travelLeft / world.travelPerStep(speed) / std::max(rate, 1e-9);
  };
  const auto finishSession = [&] {
    recordStepping(record, world);
    record.wallSeconds = wallBefore + wall();
    if (hooks.checkpoint) hooks.checkpoint(state);
  };
  const auto checkpointDue = [&] {
    if (!hooks.checkpoint || world.stepCount() % 100 != 0 || wall() - lastCheckpoint < hooks.checkpointSeconds) return;
    lastCheckpoint = wall();
    recordStepping(record, world);
    record.wallSeconds = wallBefore + wall();
    hooks.checkpoint(state);
  };

  // 1. Settle under gravity.
  while (state.phase == 0) {
    if (hooks.interrupted && hooks.interrupted()) {
      record.stopReason = "interrupted";
      return finishSession();
    }
    if (world.time() >= record.settleMaxTime) break;
    world.step();
    // Explicit: checked every 100 steps from the 1000th (damped dynamics first has to start
    // moving); implicit: each increment is a balance of forces, from the second on.
    const bool implicit = world.settings().method == SolverMethod::Implicit;
    const bool due = implicit ? world.stepCount() >= 2 : world.stepCount() % 100 == 0 && world.stepCount() >= 1000;
    if (due && world.energy().kinetic < record.settleKinetic) {
      record.settled = true;
      break;
    }
    if (hooks.progress && wall() - lastProgress >= scene.output.progressSeconds) {
      lastProgress = wall();
      const int target = centralFreeBody(bundle);
      const double h = target >= 0 ? world.bodySize(target) : 0.0;
      const double travel = scene.indenter.clearance +
                            (scene.protocol.deltaMax > 0 ? scene.protocol.deltaMax : scene.protocol.deltaMaxRatio * h);
      const EnergyBudget e = world.energy();
      // The settling's steps left to its limit, at the simulated time a step has taken so far.
      const double sessionRate = (world.stepCount() - stepsBefore) / std::max(wall(), 1e-9);
      const double settleStepsLeft = (record.settleMaxTime - world.time()) * world.stepCount() / std::max(world.time(), 1e-300);
      hooks.progress({0.0, 0.0, e.kinetic, e.obstacleWork, 0, world.stepCount(), world.stepCount() / (wallBefore + wall()),
                      eta(travel, indenterSpeed(world, scene.indenter, h)), true,
                      std::max(0.0, settleStepsLeft) / std::max(sessionRate, 1e-9)});
    }
    checkpointDue();
  }
  if (state.phase == 0) {
    record.settleTime = world.time();
    record.settleSteps = world.stepCount();
    // An assembly that does not stand under its own weight (supports, friction) is not a test.
    const RigidBodies& b = world.bodies();
    const std::vector<Eigen::Vector3d>& built = world.startPositions();
    for (int i = 0; i < static_cast<int>(b.size()); ++i)
      if (!b.fixed[i] && built[i].z() - b.position[i].z() > scene.protocol.fallenClearance * world.bodySize(i))
        ++record.sunkWhileSettling;
    if (record.sunkWhileSettling > 0 && hooks.warning)
      hooks.warning(std::to_string(record.sunkWhileSettling) + " free bodies sank by more than " +
                    std::to_string(scene.protocol.fallenClearance).substr(0, 4) +
                    " of their size while settling: the assembly does not stand under its own weight with these "
                    "supports and this friction; check the fixed bodies and material.friction");
    startLoading(world, bundle, scene, record, state);
  }

  // 2. Push at constant speed (or as the sample hook steers the indenter).
  RigidBodies& bodies = world.bodies();
  const double speed = indenterSpeed(world, scene.indenter, record.thickness);  // the protocol's
  record.indenterSpeed = speed;
  record.indenterRadius = world.sphere(state.sphere).radius;
  const double travelMax = record.deltaMax + scene.indenter.clearance + record.indenterRadius;
  bool warnedQuasiStatic = false;
  std::vector<char> out;  // bodies out at the last sample
  const auto sample = [&](double delta, double load) {
    out = updateFallen(world, scene, record, state, delta);
    const EnergyBudget e = world.energy();
    const ContactCounts c = countContacts(world, record.target);
    CurveSample s;
    s.time = world.time() - state.loadStart;
    s.delta = delta;
    s.load = load;
    s.blockDisplacement = state.settledPosition[record.target].z() - bodies.position[record.target].z();
    s.indenterPenetration = c.indenterDepth;
    s.contacts = static_cast<double>(c.all);
    s.blockContacts = static_cast<double>(c.blocks);
    s.slidingContacts = static_cast<double>(c.blocksSliding);
    s.loadedContacts = static_cast<double>(c.loaded);
    s.loadedSliding = static_cast<double>(c.loadedSliding);
    s.kinetic = e.kinetic;
    s.externalWork = e.obstacleWork;
    s.elastic = e.elastic;
    s.friction = e.friction;
    s.damping = e.damping;
    s.gravityWork = e.gravityWork;
    s.retiredKinetic = e.retiredKinetic;
    s.projection = e.projection;
    s.residual = e.residual();
    s.indenterSpeed = -world.sphere(state.sphere).velocity.z();
    record.curve.push_back(s);
  };
  // The deepest delta sampled so far (from the curve, so a resumed run knows it): the loading
  // envelope, where failure is read (run/response.cpp).
  double deepest = 0.0;
  for (const CurveSample& c : record.curve) deepest = std::max(deepest, c.delta);
  while (state.phase == 1) {
    if (hooks.interrupted && hooks.interrupted()) {
      record.stopReason = "interrupted";
      return finishSession();
    }
    world.step();
    // Travel (down) and path since loading began; with the protocol's constant speed both are speed x t.
    const double velocity = -world.sphere(state.sphere).velocity.z();
    const double travel = state.travelBase + velocity * (world.time() - state.speedSince);
    const double path = state.pathBase + std::abs(velocity) * (world.time() - state.speedSince);
    const double load = world.sphereReaction(state.sphere).z();
    if (state.contactTravel < 0 && load > 0) {
      // First contact was made within the last step, when the first node met the indenter: as far
      // back as that node has gone into it plus what the loaded block has moved down since. It
      // matters for the implicit method's increments (10 um; an explicit step moves 0.04 um).
      const double sunk = state.settledPosition[record.target].z() - bodies.position[record.target].z();
      const double past = countContacts(world, record.target).indenterDepth + std::max(sunk, 0.0);
      state.contactTravel = travel - past;
      state.contactPath = path - past;
    }
    const double delta = state.contactTravel < 0 ? 0.0 : travel - state.contactTravel;
    const double along = state.contactTravel < 0 ? 0.0 : path - state.contactPath;  // = delta while only going down
    state.peak = std::max(state.peak, load);

    // A sample every sampleEvery of path, and, when the indenter goes slower than half the
    // protocol's speed (a hold), every 2 sampleEvery / speed of time: the sample hook keeps hearing.
    // With the adaptive loading rate, a hold is slower than half its slowest speed.
    bool sampled = false, requested = false;
    const bool pathDue = along >= state.nextSample;
    const bool hold = scene.protocol.quasiStaticTarget <= 0 || std::abs(velocity) < 0.5 * kSlowestSpeedFraction * speed;
    const bool timeDue = hold && !record.curve.empty() &&
                         world.time() - state.loadStart - record.curve.back().time >= 2 * scene.output.sampleEvery / speed;
    if (state.contactTravel >= 0 && (pathDue || timeDue)) {
      sample(delta, load);
      sampled = true;
      // Quasi-static check while loading up to the peak (past the first 5 % of h of contact).
      const CurveSample& last = record.curve.back();
      if (!warnedQuasiStatic && load >= state.peak && delta > 0.05 * record.thickness && last.externalWork > 0 &&
          last.kinetic > scene.protocol.quasiStaticLimit * last.externalWork) {
        warnedQuasiStatic = true;
        if (hooks.warning)
          hooks.warning("loading too fast: kinetic energy " + std::to_string(last.kinetic / last.externalWork).substr(0, 6) +
                        " x the indenter's work at delta = " + std::to_string(delta * 1e3).substr(0, 5) +
                        " mm (limit protocol.quasi_static_limit); lower indenter.speed or indenter.speed_ratio");
      }
      state.nextSample = pathDue ? state.nextSample + scene.output.sampleEvery : along + scene.output.sampleEvery;
      // The load gone: below 1 % of the peak since quietFrom, on the loading envelope (a steered
      // indenter backing off unloads the slab; that is no failure to stop on).
      const bool onEnvelope = delta >= deepest;
      deepest = std::max(deepest, delta);
      if (state.peak > 0 && load < 0.01 * state.peak && onEnvelope) {
        if (state.quietFrom < 0) state.quietFrom = along;
      } else {
        state.quietFrom = -1;
      }
      IndentationControl control{velocity, false};
      if (hooks.sample) {
        hooks.sample(record.curve.back(), control);
        requested = control.stop;
      }
      const bool steered = control.indenterSpeed != velocity;
      if (steered && world.settings().method == SolverMethod::Explicit) {  // implicit increments follow any speed
        // The broad phase finds the indenter's contacts only if it moves less than its margin
        // between rebuilds: at most a tenth of the margin per step.
        const double fastest = 0.1 * world.settings().broadPhaseMargin / world.timeStep();
        if (!std::isfinite(control.indenterSpeed) || std::abs(control.indenterSpeed) > fastest) {
          record.stopReason = "interrupted";  // as stopped here: resumable, its checkpoint written
          finishSession();
          throw std::invalid_argument("the sample hook set the indenter speed to " + std::to_string(control.indenterSpeed) +
                                      " m/s; it must be finite and at most " + std::to_string(fastest) +
                                      " m/s (a tenth of the broad-phase margin per time step)");
        }
      }
      // Adaptive loading rate, from first contact until the load first falls below half its
      // largest value (past the peak), or a sample hook sets the speed (it steers from then on):
      // the speed that keeps KE / W under the target.
      if (scene.protocol.quasiStaticTarget > 0 && (steered || (state.peak > 0 && load < 0.5 * state.peak)))
        state.rateAdapted = true;
      if (scene.protocol.quasiStaticTarget > 0 && !state.rateAdapted && last.externalWork > 0 && velocity > 0) {
        double recent = 0;
        const std::size_t n = record.curve.size();
        for (std::size_t i = n - std::min<std::size_t>(n, kRecentSamples); i < n; ++i)
          if (record.curve[i].externalWork > 0) recent = std::max(recent, record.curve[i].kinetic / record.curve[i].externalWork);
        control.indenterSpeed = adaptedIndenterSpeed(velocity, last.kinetic / last.externalWork, recent,
                                                     scene.protocol.quasiStaticTarget, kSlowestSpeedFraction * speed, speed);
      }
      if (control.indenterSpeed != velocity) {
        state.travelBase = travel;
        state.pathBase = path;
        state.speedSince = world.time();
        world.sphere(state.sphere).velocity = Eigen::Vector3d(0, 0, -control.indenterSpeed);
      }
    }
    if (state.contactTravel >= 0 && along >= state.nextSnapshot) {
      record.snapshots.push_back(snapshotOf(world, state.sphere, delta, load));
      state.nextSnapshot += scene.output.snapshotEvery;
    }

    if (hooks.progress && wall() - lastProgress >= scene.output.progressSeconds) {
      lastProgress = wall();
      // Travel left: to first contact (the clearance) and on to delta_max.
      const double left = state.contactTravel < 0 ? scene.indenter.clearance - travel + record.deltaMax
                                                  : record.deltaMax - delta;
      const EnergyBudget e = world.energy();
      hooks.progress({delta, load, e.kinetic, e.obstacleWork, static_cast<long>(countContacts(world, record.target).all),
                      world.stepCount(), world.stepCount() / (wallBefore + wall()),
                      eta(std::max(left, 0.0), velocity > 0 ? velocity : speed), false, 0.0});
    }
    const bool reachedMax = (state.contactTravel >= 0 && delta >= record.deltaMax) ||
                            travel > travelMax + record.deltaMax;  // the latter: never touched anything
    const bool failed = scene.protocol.stopOnFailure && sampled && state.quietFrom >= 0 &&
                        along - state.quietFrom >= scene.protocol.quietTravel * record.thickness &&
                        restingBodies(world, out, scene.protocol.restSpeedRatio * speed);
    if (reachedMax || failed || requested) {
      record.stopReason = requested ? "requested" : failed ? "failure" : "delta_max";
      // The state at the stop closes the curve.
      if (state.contactTravel >= 0 && (record.curve.empty() || record.curve.back().time < world.time() - state.loadStart))
        sample(delta, load);
      if (!record.curve.empty() && (record.snapshots.empty() || record.snapshots.back().delta != record.curve.back().delta))
        record.snapshots.push_back(snapshotOf(world, state.sphere, delta, load));
      state.phase = 2;
      break;
    }
    checkpointDue();
  }
  finishSession();
}

}  // namespace tessera

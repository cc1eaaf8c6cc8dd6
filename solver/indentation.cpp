#include "solver/indentation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tessera {

int centralFreeBody(const World& world) {
  const RigidBodies& b = world.bodies();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < b.size(); ++i) centre += b.position[i].head<2>() / static_cast<double>(b.size());
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.fixed[i]) continue;
    const double d = (b.position[i].head<2>() - centre).norm();
    if (d < bestDistance - 1e-12) {
      bestDistance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

namespace {

Snapshot snapshotOf(const World& world, double delta, double load) {
  Snapshot s{delta, load, world.bodies().position, world.bodies().orientation, {}};
  for (const PairContacts& p : world.pairs())
    if (!p.contacts.empty()) s.forces.push_back({p.a, p.b, p.forcePoint, p.forceA});
  return s;
}

long nodeContacts(const World& world) {
  long n = 0;
  for (const PairContacts& p : world.pairs()) n += static_cast<long>(p.contacts.size());
  return n;
}

// After settling: choose the target, place the indenter just above its top.
void startLoading(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                  IndentationState& state) {
  RigidBodies& bodies = world.bodies();
  record.target = -1;
  if (!scene.indenter.target.empty()) {
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (bodies.name[i] == scene.indenter.target) record.target = static_cast<int>(i);
    if (record.target < 0) throw std::invalid_argument("indenter.target '" + scene.indenter.target + "' is not a body of the bundle");
  } else {
    record.target = centralFreeBody(world);
    if (record.target < 0) throw std::invalid_argument("the bundle has no free body to load");
  }
  record.targetName = bodies.name[record.target];
  double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
  for (const auto& v : bundle.shapes[bodies.shape[record.target]].mesh.vertices) {
    const double z = (bodies.orientation[record.target] * v + bodies.position[record.target]).z();
    top = std::max(top, z);
    bottom = std::min(bottom, z);
  }
  state.fallenDistance = scene.protocol.fallenDistance > 0 ? scene.protocol.fallenDistance : top - bottom;
  SphereObstacle indenter;
  indenter.radius = scene.indenter.radius;
  indenter.center = bodies.position[record.target];
  indenter.center.z() = top + scene.indenter.radius + scene.indenter.clearance;
  indenter.velocity = Eigen::Vector3d(0, 0, -scene.indenter.speed);
  state.sphere = world.addSphere(indenter);
  state.settledPosition = bodies.position;
  state.targetZ0 = bodies.position[record.target].z();
  state.loadStart = world.time();
  state.phase = 1;
}

}  // namespace

void runIndentation(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                    IndentationState& state, const RunHooks& hooks) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double wallBefore = record.wallSeconds;
  const auto wall = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  record.timeStep = world.timeStep();
  double lastProgress = wall(), lastCheckpoint = wall();
  const auto finishSession = [&] {
    record.steps = world.stepCount();
    record.wallSeconds = wallBefore + wall();
    if (hooks.checkpoint) hooks.checkpoint(state);
  };
  const auto checkpointDue = [&] {
    if (!hooks.checkpoint || world.stepCount() % 100 != 0 || wall() - lastCheckpoint < hooks.checkpointSeconds) return;
    lastCheckpoint = wall();
    record.steps = world.stepCount();
    record.wallSeconds = wallBefore + wall();
    hooks.checkpoint(state);
  };

  // 1. Settle under gravity.
  while (state.phase == 0) {
    if (hooks.interrupted()) {
      record.stopReason = "interrupted";
      return finishSession();
    }
    if (world.time() >= scene.protocol.settleMaxTime) break;
    world.step();
    if (world.stepCount() % 100 == 0 && world.stepCount() >= 1000 && world.energy().kinetic < scene.protocol.settleKinetic) {
      record.settled = true;
      break;
    }
    checkpointDue();
  }
  if (state.phase == 0) {
    record.settleTime = world.time();
    record.settleSteps = world.stepCount();
    startLoading(world, bundle, scene, record, state);
  }

  // 2. Push at constant speed.
  RigidBodies& bodies = world.bodies();
  const double speed = scene.indenter.speed;
  const double travelMax = scene.protocol.deltaMax + scene.indenter.clearance + scene.indenter.radius;
  const auto sample = [&](double delta, double load) {
    const EnergyBudget e = world.energy();
    record.curve.push_back({world.time() - state.loadStart, delta, load, e.kinetic, e.obstacleWork, e.elastic,
                            nodeContacts(world),
                            world.isRetired(record.target) ? state.fallenDistance
                                                           : state.targetZ0 - bodies.position[record.target].z()});
  };
  while (state.phase == 1) {
    if (hooks.interrupted()) {
      record.stopReason = "interrupted";
      return finishSession();
    }
    world.step();
    const double travel = speed * (world.time() - state.loadStart);
    const double load = world.sphereReaction(state.sphere).z();
    if (state.contactTravel < 0 && load > 0) state.contactTravel = travel;
    const double delta = state.contactTravel < 0 ? 0.0 : travel - state.contactTravel;

    // Retire bodies that have fallen clear.
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (!bodies.fixed[i] && state.settledPosition[i].z() - bodies.position[i].z() > state.fallenDistance) {
        record.fallen.push_back({bodies.name[i], delta});
        world.retireBody(static_cast<int>(i));
      }

    if (state.contactTravel >= 0 && delta >= state.nextSample) {
      sample(delta, load);
      state.nextSample += scene.output.sampleEvery;
    }
    if (state.contactTravel >= 0 && delta >= state.nextSnapshot) {
      record.snapshots.push_back(snapshotOf(world, delta, load));
      state.nextSnapshot += scene.output.snapshotEvery;
    }
    state.peak = std::max(state.peak, load);

    if (hooks.progress && wall() - lastProgress >= scene.output.progressSeconds) {
      lastProgress = wall();
      const double done = std::max(travel / travelMax, 1e-9);
      hooks.progress({delta, load, world.energy().kinetic, world.energy().obstacleWork, nodeContacts(world),
                      world.stepCount(), world.stepCount() / (wallBefore + wall()), (wallBefore + wall()) * (1 - done) / done});
    }
    const bool reachedMax = (state.contactTravel >= 0 && delta >= scene.protocol.deltaMax) ||
                            travel > travelMax + scene.protocol.deltaMax;  // the latter: never touched anything
    const bool failed = scene.protocol.stopOnFailure && state.peak > 0 && world.isRetired(record.target) &&
                        load <= 0.01 * state.peak;
    if (reachedMax || failed) {
      record.stopReason = failed ? "failure" : "delta_max";
      // The state at the stop closes the curve (the drop to zero of a failure, for one).
      if (state.contactTravel >= 0 && (record.curve.empty() || record.curve.back().time < world.time() - state.loadStart))
        sample(delta, load);
      if (!record.curve.empty() && (record.snapshots.empty() || record.snapshots.back().delta < record.curve.back().delta))
        record.snapshots.push_back(snapshotOf(world, delta, load));
      state.phase = 2;
      break;
    }
    checkpointDue();
  }
  finishSession();
}

}  // namespace tessera

#include "solver/indentation.h"

#include "solver/assembly_state.h"

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

// After settling: choose the target, measure its thickness, place the indenter just above its top.
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
  // h: the settled block's extent along the loading direction (z), from its mesh as posed.
  double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
  for (const auto& v : bundle.shapes[bodies.shape[record.target]].mesh.vertices) {
    const double z = (bodies.orientation[record.target] * v + bodies.position[record.target]).z();
    top = std::max(top, z);
    bottom = std::min(bottom, z);
  }
  record.thickness = top - bottom;
  record.deltaMax = scene.protocol.deltaMax > 0 ? scene.protocol.deltaMax : scene.protocol.deltaMaxRatio * record.thickness;
  SphereObstacle indenter;
  indenter.radius = scene.indenter.radius;
  indenter.center = bodies.position[record.target];
  indenter.center.z() = top + scene.indenter.radius + scene.indenter.clearance;
  indenter.velocity = Eigen::Vector3d(0, 0, -scene.indenter.speed);
  indenter.stiffnessFactor = scene.indenter.stiffnessFactor;
  state.sphere = world.addSphere(indenter);
  state.settledPosition = bodies.position;
  state.outAt.assign(bodies.size(), -1.0);
  state.loadStart = world.time();
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
  const double travelMax = record.deltaMax + scene.indenter.clearance + scene.indenter.radius;
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
    record.curve.push_back(s);
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
    state.peak = std::max(state.peak, load);

    bool sampled = false;
    if (state.contactTravel >= 0 && delta >= state.nextSample) {
      sample(delta, load);
      sampled = true;
      state.nextSample += scene.output.sampleEvery;
      // The load gone: below 1 % of the peak since quietFrom.
      if (state.peak > 0 && load < 0.01 * state.peak) {
        if (state.quietFrom < 0) state.quietFrom = delta;
      } else {
        state.quietFrom = -1;
      }
    }
    if (state.contactTravel >= 0 && delta >= state.nextSnapshot) {
      record.snapshots.push_back(snapshotOf(world, delta, load));
      state.nextSnapshot += scene.output.snapshotEvery;
    }

    if (hooks.progress && wall() - lastProgress >= scene.output.progressSeconds) {
      lastProgress = wall();
      const double done = std::max(travel / travelMax, 1e-9);
      const EnergyBudget e = world.energy();
      hooks.progress({delta, load, e.kinetic, e.obstacleWork, static_cast<long>(countContacts(world, record.target).all),
                      world.stepCount(), world.stepCount() / (wallBefore + wall()), (wallBefore + wall()) * (1 - done) / done});
    }
    const bool reachedMax = (state.contactTravel >= 0 && delta >= record.deltaMax) ||
                            travel > travelMax + record.deltaMax;  // the latter: never touched anything
    const bool failed = scene.protocol.stopOnFailure && sampled && state.quietFrom >= 0 &&
                        delta - state.quietFrom >= scene.protocol.quietTravel * record.thickness &&
                        restingBodies(world, out, scene.protocol.restSpeedRatio * scene.indenter.speed);
    if (reachedMax || failed) {
      record.stopReason = failed ? "failure" : "delta_max";
      // The state at the stop closes the curve.
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

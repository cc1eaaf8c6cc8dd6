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

long nodeContacts(const World& world) {
  long n = 0;
  for (const PairContacts& p : world.pairs()) n += static_cast<long>(p.contacts.size());
  return n;
}

Snapshot snapshotOf(const World& world, double delta, double load) {
  return Snapshot{delta, load, world.bodies().position, world.bodies().orientation};
}

}  // namespace

void runIndentation(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                    const std::function<void(const Progress&)>& progress, const std::function<bool()>& interrupted) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  record.timeStep = world.timeStep();
  const auto wall = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  // 1. Settle under gravity.
  while (world.time() < scene.protocol.settleMaxTime) {
    world.step();
    if (world.stepCount() % 100 == 0 && world.stepCount() >= 1000 && world.energy().kinetic < scene.protocol.settleKinetic) {
      record.settled = true;
      break;
    }
    if (interrupted()) {
      record.stopReason = "interrupted";
      return;
    }
  }
  record.settleTime = world.time();
  record.settleSteps = world.stepCount();

  // 2. Target and indenter.
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
  const Shape& targetShape = bundle.shapes[bodies.shape[record.target]];
  double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
  for (const auto& v : targetShape.mesh.vertices) {
    const double z = (bodies.orientation[record.target] * v + bodies.position[record.target]).z();
    top = std::max(top, z);
    bottom = std::min(bottom, z);
  }
  const double fallenDistance = scene.protocol.fallenDistance > 0 ? scene.protocol.fallenDistance : top - bottom;
  SphereObstacle indenter;
  indenter.radius = scene.indenter.radius;
  indenter.center = bodies.position[record.target];
  indenter.center.z() = top + scene.indenter.radius + scene.indenter.clearance;
  indenter.velocity = Eigen::Vector3d(0, 0, -scene.indenter.speed);
  const int sphere = world.addSphere(indenter);
  const std::vector<Eigen::Vector3d> settledPosition = bodies.position;
  const double targetZ0 = bodies.position[record.target].z();

  // 3. Push at constant speed.
  const double loadStart = world.time();
  double contactTravel = -1;  // indenter travel at first contact
  double peak = 0;
  double nextSample = 0, nextSnapshot = 0, lastProgress = wall();
  const auto sample = [&](double delta, double load) {
    const EnergyBudget e = world.energy();
    record.curve.push_back({world.time() - loadStart, delta, load, e.kinetic, e.obstacleWork, e.elastic,
                            nodeContacts(world),
                            world.isRetired(record.target) ? fallenDistance : targetZ0 - bodies.position[record.target].z()});
  };
  const double travelMax = scene.protocol.deltaMax + scene.indenter.clearance + scene.indenter.radius;
  for (;;) {
    if (interrupted()) {
      record.stopReason = "interrupted";
      break;
    }
    world.step();
    const double travel = scene.indenter.speed * (world.time() - loadStart);
    const double load = world.sphereReaction(sphere).z();
    if (contactTravel < 0 && load > 0) contactTravel = travel;
    const double delta = contactTravel < 0 ? 0.0 : travel - contactTravel;

    // Retire bodies that have fallen clear.
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (!bodies.fixed[i] && settledPosition[i].z() - bodies.position[i].z() > fallenDistance) {
        record.fallen.push_back({bodies.name[i], delta});
        world.retireBody(static_cast<int>(i));
      }

    if (contactTravel >= 0 && delta >= nextSample) {
      sample(delta, load);
      nextSample += scene.output.sampleEvery;
    }
    if (contactTravel >= 0 && delta >= nextSnapshot) {
      record.snapshots.push_back(snapshotOf(world, delta, load));
      nextSnapshot += scene.output.snapshotEvery;
    }
    peak = std::max(peak, load);

    if (wall() - lastProgress >= scene.output.progressSeconds) {
      lastProgress = wall();
      const double done = std::max(travel / travelMax, 1e-9);
      progress({delta, load, world.energy().kinetic, world.energy().obstacleWork, nodeContacts(world), world.stepCount(),
                world.stepCount() / wall(), wall() * (1 - done) / done});
    }
    if (contactTravel >= 0 && delta >= scene.protocol.deltaMax) {
      record.stopReason = "delta_max";
      break;
    }
    if (travel > travelMax + scene.protocol.deltaMax) {  // never touched anything
      record.stopReason = "delta_max";
      break;
    }
    if (scene.protocol.stopOnFailure && peak > 0 && world.isRetired(record.target) && load <= 0.01 * peak) {
      record.stopReason = "failure";
      break;
    }
  }
  // The state at the stop closes the curve (the drop to zero of a failure, for one).
  if (contactTravel >= 0 && (record.curve.empty() || record.curve.back().time < world.time() - loadStart))
    sample(scene.indenter.speed * (world.time() - loadStart) - contactTravel, world.sphereReaction(sphere).z());
  if (!record.curve.empty() && record.snapshots.back().delta < record.curve.back().delta)
    record.snapshots.push_back(snapshotOf(world, record.curve.back().delta, record.curve.back().load));
  record.steps = world.stepCount();
  record.wallSeconds = wall();
}

}  // namespace tessera

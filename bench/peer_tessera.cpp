// Tessera's half of the side-by-side with YADE's LS-DEM (bench/peer_yade.sh runs both).
//
//   peer_tessera step BUNDLE_DIR THREADS DT STEPS   time per step on the slab of the bundle, pushed
//       together by 5 um (every block 0.05 % closer to the centre, so that every side face
//       overlaps), outer ring fixed, gravity, the 2.5 mm indenter 20 um into the centre block,
//       at the fixed step DT. Grid level sets (as YADE has), the bundle's nodes.
//   peer_tessera rest DT                 a 10 x 10 x 3.18 mm box resting on a fixed one: mean contact
//       force / weight, and its step-to-step spread (std / mean) over the last 20 % of 0.05 s.
//   peer_tessera incline DEGREES DT      the same box on the fixed box, gravity tilted by DEGREES
//       (mu = 0.23, atan mu = 12.95 deg): slip along the slope after 0.05 s.
// Material: E = 4.2 GPa (k_n = E M / L with the default slab's M = 6, L = 50 mm), density 2500,
// Cundall's local damping 0.3. Prints one JSON object.
#include "geometry/block_generators.h"
#include "levelset/bundle.h"
#include "levelset/shape_builder.h"
#include "solver/world.h"
#include "solver/world_internals.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace tessera;

namespace {

const double kSide = 10e-3, kThickness = 3.18e-3, kMu = 0.23;

SolverSettings settings(double dt, int threads) {
  SolverSettings s;
  s.timeStep = dt;
  s.threads = threads;
  s.localDamping = 0.3;
  s.exactConvexLevelSets = false;  // grids, as in YADE
  return s;
}

ContactParameters material() {
  ContactParameters p;
  p.friction = kMu;
  return p;
}

int stepTiming(const std::string& bundleDir, int threads, double dt, int steps) {
  Bundle slab = readBundle(bundleDir);
  for (Body& b : slab.bodies) b.position.head<2>() *= 1 - 5e-4;
  World world(slab.shapes, slab.bodies, material(), settings(dt, threads));
  SphereObstacle indenter;
  indenter.center = Eigen::Vector3d(0, 0, kThickness / 2 + indenter.radius - 20e-6);
  world.addSphere(indenter);
  for (int i = 0; i < 100; ++i) world.step();
  long contacts = 0, evaluations = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    world.step();
    for (const PairContacts& p : WorldInternals::pairs(world)) {
      contacts += static_cast<long>(p.contacts.size());
      evaluations += p.evaluations;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("{\"code\": \"tessera\", \"threads\": %d, \"us_per_step\": %.2f, \"node_contacts_per_step\": %.0f, "
              "\"node_evaluations_per_step\": %.0f, \"nodes_per_block\": %zu, \"pairs\": %zu}\n",
              threads, 1e6 * seconds / steps, static_cast<double>(contacts) / steps,
              static_cast<double>(evaluations) / steps, slab.shapes[0].nodes.size(), WorldInternals::pairs(world).size());
  return 0;
}

// A fixed box and a box resting on it (their faces just touching), under gravity g.
World stackedBoxes(double dt, const Eigen::Vector3d& gravity) {
  ShapeResolution r;  // 0.25 mm voxels, 0.6 mm nodes
  PrepLog log;
  static const Shape box = buildShape("box", makeBox(kSide, kSide, kThickness), {}, r, "box", log);
  Bundle b;
  b.shapes.push_back(box);
  Body base, top;
  base.name = "base";
  base.fixed = true;
  top.name = "top";
  top.position = Eigen::Vector3d(0, 0, kThickness);
  b.bodies = {base, top};
  SolverSettings s = settings(dt, 1);
  s.gravity = gravity;
  return World(b.shapes, b.bodies, material(), s);
}

int resting(double dt) {
  World world = stackedBoxes(dt, Eigen::Vector3d(0, 0, -9.81));
  const double weight = world.bodies().mass[1] * 9.81;
  const int steps = static_cast<int>(0.05 / dt), from = steps * 4 / 5;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < steps; ++i) {
    world.step();
    if (i < from) continue;
    const double f = world.contactForces()[1].z();
    sum += f;
    sum2 += f * f;
  }
  const int n = steps - from;
  const double mean = sum / n, spread = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  std::printf("{\"code\": \"tessera\", \"check\": \"rest\", \"force_over_weight\": %.6f, \"spread_over_mean\": %.3e}\n",
              mean / weight, spread / mean);
  return 0;
}

int incline(double degrees, double dt) {
  const double theta = degrees * M_PI / 180;
  // Tilting the blocks by theta is tilting gravity by -theta.
  World world = stackedBoxes(dt, 9.81 * Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta)));
  const double x0 = world.bodies().position[1].x();
  while (world.time() < 0.05) world.step();
  std::printf("{\"code\": \"tessera\", \"check\": \"incline\", \"degrees\": %.2f, \"slip_m\": %.4e}\n", degrees,
              world.bodies().position[1].x() - x0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "step" && argc == 6) return stepTiming(argv[2], std::atoi(argv[3]), std::atof(argv[4]), std::atoi(argv[5]));
    if (mode == "rest" && argc == 3) return resting(std::atof(argv[2]));
    if (mode == "incline" && argc == 4) return incline(std::atof(argv[2]), std::atof(argv[3]));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_tessera: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr,
               "usage: peer_tessera step BUNDLE_DIR THREADS DT STEPS | rest DT | incline DEGREES DT (see the source)\n");
  return 2;
}

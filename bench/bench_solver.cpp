// Solver speed on the default slab (7 x 7 planar blocks, 0.6 mm nodes, 0.25 mm voxels) and on
// 15 x 15 and 31 x 31 slabs of the same block during indentation: time per step, per node contact
// and node-vs-level-set evaluations per second per core, with 1 and 2 threads, for the exact
// convex level sets (default), the exact mesh level sets and the grids; and the free rotation of
// every body, the largest serial part of a step.
// Run: build/bench/bench_solver --benchmark_min_time=3   (results: bench/README.md)
#include "bench/default_slab.h"
#include "solver/world.h"
#include "solver/world_internals.h"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

using namespace tessera;

namespace {

const Bundle& slab(int blocksPerSide) {
  static std::map<int, Bundle> slabs;
  auto [it, added] = slabs.try_emplace(blocksPerSide);
  if (added) {
    it->second = bench::defaultSlab(blocksPerSide);
    for (Shape& shape : it->second.shapes) deriveExactMesh(shape);  // for path 1, as a run does
  }
  return it->second;
}

// Arguments: threads, level-set path (0 exact planes, 1 exact mesh, 2 grid), blocks per side.
void IndentationStep(benchmark::State& state) {
  SolverSettings s;
  s.threads = static_cast<int>(state.range(0));
  s.exactConvexLevelSets = state.range(1) == 0;
  s.exactMeshLevelSets = state.range(1) == 1;
  s.localDamping = 0.3;
  const Bundle bundle = slab(static_cast<int>(state.range(2)));
  World world(bundle.shapes, bundle.bodies, ContactParameters{}, s);
  SphereObstacle indenter;
  indenter.center = Eigen::Vector3d(0, 0, 1.59e-3 + 2.5e-3 - 0.02e-3);  // already pressing
  indenter.velocity = Eigen::Vector3d(0, 0, -6e-3);
  world.addSphere(indenter);
  for (int i = 0; i < 200; ++i) world.step();  // contacts established, springs loaded
  long evaluations = 0, contacts = 0;
  for (auto _ : state) {
    world.step();
    for (const PairContacts& p : WorldInternals::pairs(world)) {
      evaluations += p.evaluations;
      contacts += static_cast<long>(p.contacts.size());
    }
  }
  state.counters["contacts_per_step"] = benchmark::Counter(static_cast<double>(contacts) / state.iterations());
  state.counters["evaluations_per_step"] = benchmark::Counter(static_cast<double>(evaluations) / state.iterations());
  // Wall time per node contact (time / contacts, in ns).
  state.counters["ns_per_contact"] =
      benchmark::Counter(static_cast<double>(contacts) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["evaluations_per_s_per_core"] =
      benchmark::Counter(static_cast<double>(evaluations) / static_cast<double>(s.threads), benchmark::Counter::kIsRate);
  state.counters["pairs"] = static_cast<double>(WorldInternals::pairs(world).size());
}

// The free rotation of every free body of a slab (serial, once a step): ns per free body (the
// perimeter is fixed). Argument: blocks per side. Each body spins at 1.9 rad/s about a tilted axis.
void FreeRotation(benchmark::State& state) {
  const Bundle bundle = slab(static_cast<int>(state.range(0)));
  RigidBodies bodies = makeRigidBodies(bundle.shapes, bundle.bodies, 2500.0);
  std::size_t free = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies.angularMomentum[i] = bodies.inertia[i].cwiseProduct(Eigen::Vector3d(1.0, 0.5, -1.5));
    free += bodies.fixed[i] ? 0 : 1;
  }
  const double dt = 1.28e-6;  // s, the paper slab's step
  for (auto _ : state) {
    rotateFreely(bodies, dt);
    benchmark::DoNotOptimize(bodies.orientation.data());
  }
  state.counters["ns_per_free_body"] =
      benchmark::Counter(static_cast<double>(free) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(FreeRotation)->ArgName("side")->Arg(7)->Arg(31)->Unit(benchmark::kMicrosecond);
BENCHMARK(IndentationStep)
    ->ArgNames({"threads", "path", "side"})
    ->Args({1, 0, 7})->Args({2, 0, 7})->Args({1, 1, 7})->Args({2, 1, 7})->Args({1, 2, 7})->Args({2, 2, 7})
    ->Args({1, 0, 15})->Args({2, 0, 15})->Args({1, 0, 31})->Args({2, 0, 31})
    ->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_MAIN();

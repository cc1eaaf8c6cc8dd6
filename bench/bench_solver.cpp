// Solver speed on the default slab (7 x 7 planar blocks, 0.6 mm nodes, 0.25 mm voxels) during
// indentation: time per step and node-vs-level-set evaluations per second per core, with 1 and
// 2 threads, for the exact convex level sets (default), the exact mesh level sets and the grids.
// Run: build/bench/bench_solver --benchmark_min_time=3   (results: bench/README.md)
#include "bench/default_slab.h"
#include "solver/world.h"

#include <benchmark/benchmark.h>

#include <memory>

using namespace tessera;

namespace {

const Bundle& defaultSlab() {
  static const Bundle slab = [] {
    Bundle b = bench::defaultSlab();
    for (Shape& shape : b.shapes) deriveExactMesh(shape);  // for path 1, as a run does
    return b;
  }();
  return slab;
}

// Arguments: threads, level-set path (0 exact planes, 1 exact mesh, 2 grid).
void IndentationStep(benchmark::State& state) {
  SolverSettings s;
  s.threads = static_cast<int>(state.range(0));
  s.exactConvexLevelSets = state.range(1) == 0;
  s.exactMeshLevelSets = state.range(1) == 1;
  s.localDamping = 0.3;
  World world(defaultSlab(), ContactParameters{}, s);
  SphereObstacle indenter;
  indenter.center = Eigen::Vector3d(0, 0, 1.59e-3 + 2.5e-3 - 0.02e-3);  // already pressing
  indenter.velocity = Eigen::Vector3d(0, 0, -6e-3);
  world.addSphere(indenter);
  for (int i = 0; i < 200; ++i) world.step();  // contacts established, springs loaded
  long evaluations = 0, contacts = 0;
  for (auto _ : state) {
    world.step();
    for (const PairContacts& p : world.pairs()) {
      evaluations += p.evaluations;
      contacts += static_cast<long>(p.contacts.size());
    }
  }
  state.counters["contacts_per_step"] = benchmark::Counter(static_cast<double>(contacts) / state.iterations());
  state.counters["evaluations_per_step"] = benchmark::Counter(static_cast<double>(evaluations) / state.iterations());
  state.counters["evaluations_per_s_per_core"] =
      benchmark::Counter(static_cast<double>(evaluations) / static_cast<double>(s.threads), benchmark::Counter::kIsRate);
  state.counters["pairs"] = static_cast<double>(world.pairs().size());
}

}  // namespace

BENCHMARK(IndentationStep)
    ->ArgNames({"threads", "path"})
    ->Args({1, 0})->Args({2, 0})->Args({1, 1})->Args({2, 1})->Args({1, 2})->Args({2, 2})
    ->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_MAIN();

// Cost of one level-set evaluation at points near a block's surface (within 2 voxels, inside and
// out, where the contact loop evaluates its candidate nodes), by path: the exact planes of a
// convex block, the exact mesh level set (closest triangle of the cell's list, pseudo-normal sign),
// and the trilinear grid; and the exact mesh as a run evaluates it, each point with the
// MeshSdf::NearestFace its last evaluation kept and moved 0.1 um between evaluations (a step moves
// a node by less). Blocks: the paper's planar block (convex) and the wave block (not), at
// the paper's resolution (0.25 mm voxels). One thread.
// Run: build/bench/bench_level_set --benchmark_min_time=2   (results: docs/performance.md)
#include "geometry/block_generators.h"
#include "levelset/shape_builder.h"
#include "solver/pair_contacts.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

using namespace tessera;

namespace {

struct Block {
  ShapeModel model;
  std::vector<Eigen::Vector3d> points;
  double meanList = 0;  // triangles listed per cell, over the cells the points fall in
  double exactKiB = 0;  // memory of the exact mesh level set: triangles, cell index and lists
  double gridKiB = 0;   // memory of the grid's values
};

Block makeBlock(bool wave) {
  const double theta = 5.0 * M_PI / 180;
  TriangleMesh mesh = wave ? makeWaveBlock(10e-3, 3.18e-3, theta, 0.2e-3, 1, 24) : makePlanarBlock(10e-3, 3.18e-3, theta);
  PrepLog log;
  Shape shape = buildShape(wave ? "wave" : "planar", std::move(mesh), {}, {}, "bench", log);
  deriveExactMesh(shape);
  Block b;
  b.model.sdf = shape.sdf;
  b.model.exactMesh = shape.exactMesh;
  if (shape.convex) b.model.planes = shape.convex->planes;
  std::mt19937 random(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d lo = shape.sdf.origin, span = shape.sdf.upperCorner() - lo;
  while (b.points.size() < 4096) {
    const Eigen::Vector3d x = lo + span.cwiseProduct(Eigen::Vector3d(unit(random), unit(random), unit(random)));
    if (std::abs(shape.sdf.value(x)) < 2 * shape.sdf.voxelSize) b.points.push_back(x);
  }
  const MeshSdf& m = shape.exactMesh;
  b.exactKiB = (m.triangles.size() * sizeof(MeshSdf::Triangle) + m.cellStart.size() * sizeof(std::uint32_t) +
                m.cellTriangles.size() * sizeof(std::uint32_t) + m.centreDistance.size() * sizeof(float)) / 1024.0;
  b.gridKiB = shape.sdf.values.size() * sizeof(float) / 1024.0;
  for (const Eigen::Vector3d& x : b.points) {
    const Eigen::Vector3i c = ((x - m.origin) / m.cellSize).cast<int>();
    const std::size_t cell = (static_cast<std::size_t>(c[0]) * m.cells[1] + c[1]) * m.cells[2] + c[2];
    b.meanList += (m.cellStart[cell + 1] - m.cellStart[cell]) / double(b.points.size());
  }
  return b;
}

const Block& block(bool wave) {
  static const Block planar = makeBlock(false), waveBlock = makeBlock(true);
  return wave ? waveBlock : planar;
}

// Arguments: block (0 planar, 1 wave), path (0 planes, 1 exact mesh, 2 grid, 3 exact mesh with
// each point's NearestFace kept).
void LevelSetEvaluation(benchmark::State& state) {
  const Block& b = block(state.range(0) == 1);
  const int path = static_cast<int>(state.range(1));
  if (path == 0 && b.model.planes.empty()) {
    state.SkipWithError("not convex: no planes");
    return;
  }
  double sum = 0;
  std::size_t k = 0;
  std::vector<MeshSdf::NearestFace> kept(b.points.size());
  const Eigen::Vector3d shift = Eigen::Vector3d(1, 2, 3).normalized() * 1e-7;
  for (auto _ : state) {
    const std::size_t i = k & 4095, pass = k++ >> 12;
    // (Path 3 moves every other pass over the points by `shift`, so that the kept NearestFace is
    // tested at a point it was not made at.)
    const Eigen::Vector3d x = path == 3 && (pass & 1) != 0 ? Eigen::Vector3d(b.points[i] + shift) : b.points[i];
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    double phi;
    if (path == 0) {
      phi = planesLevelSet(b.model.planes, x);
    } else if (path == 1) {
      phi = b.model.meshLevelSet(x, normal);
    } else if (path == 3) {
      phi = b.model.meshLevelSet(x, b.model.sdf.value(x), normal, &kept[i]);
    } else {
      phi = b.model.gridLevelSet(x, normal);
    }
    sum += phi + normal.x();
    benchmark::DoNotOptimize(sum);
  }
  state.counters["triangles_per_cell"] = b.meanList;
  state.counters["exact_mesh_KiB"] = b.exactKiB;
  state.counters["grid_KiB"] = b.gridKiB;
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

BENCHMARK(LevelSetEvaluation)
    ->ArgNames({"wave", "path"})
    ->Args({0, 0})->Args({0, 1})->Args({0, 2})->Args({0, 3})->Args({1, 1})->Args({1, 2})->Args({1, 3})
    ->Unit(benchmark::kNanosecond);
BENCHMARK_MAIN();

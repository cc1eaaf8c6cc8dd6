// How long `tessera prep` takes for the default block (10 x 10 x 3.18 mm, 5 deg) at the paper's
// resolution (0.25 mm voxels, 0.6 mm nodes) and at half those sizes, stage by stage.
// Run: build/bench/bench_prep --benchmark_min_time=2   (results: bench/README.md)
#include "geometry/mass_properties.h"
#include "geometry/mesh_features.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_validation.h"
#include "geometry/surface_nodes.h"
#include "levelset/bundle.h"
#include "levelset/shape_builder.h"
#include "levelset/signed_distance.h"

#include <benchmark/benchmark.h>

#include <filesystem>

using namespace tessera;

namespace {

const std::string kBlock = TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj";

// Argument: refinement r; voxel 0.25 / r mm, spacing 0.6 / r mm.
ShapeResolution resolution(const benchmark::State& state) {
  ShapeResolution r;
  r.voxelSize = 0.25e-3 / static_cast<double>(state.range(0));
  r.nodeSpacing = 0.6e-3 / static_cast<double>(state.range(0));
  return r;
}

TriangleMesh bodyMesh() {
  MeshImportOptions options;
  options.metresPerUnit = 1e-3;
  TriangleMesh mesh = importMesh(kBlock, options).mesh;
  validateSolidMesh(mesh, kBlock);
  return toBodyFrame(mesh, computeMassProperties(mesh));
}

void PrepWhole(benchmark::State& state) {  // import, validate, measure, nodes, grid, write bundle
  const ShapeResolution r = resolution(state);
  const std::string out = std::filesystem::temp_directory_path() / "tessera-bench-prep";
  for (auto _ : state) {
    PrepLog log;
    Bundle bundle;
    bundle.shapes.push_back(prepareShapeFromFile(kBlock, "mm", "planar", r, log));
    writeBundle(out, bundle);
  }
  std::filesystem::remove_all(out);
}

void ImportAndValidate(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(bodyMesh());
}

// Arg 1: with the block's symmetries (1, the default) or without (0).
void SurfaceNodesStage(benchmark::State& state) {
  const TriangleMesh mesh = bodyMesh();
  SurfaceNodeOptions options;
  options.spacing = resolution(state).nodeSpacing;
  options.keepSymmetries = state.range(1) != 0;
  for (auto _ : state) {
    const MeshFeatures features = findFeatures(mesh, options.featureAngle);
    const SurfaceNodes nodes = sampleSurfaceNodes(mesh, features, options);
    state.counters["nodes"] = static_cast<double>(nodes.size());
  }
}

void SignedDistanceStage(benchmark::State& state) {
  const TriangleMesh mesh = bodyMesh();
  SignedDistanceOptions options;
  options.voxelSize = resolution(state).voxelSize;
  for (auto _ : state) {
    const DenseSdf sdf = buildSignedDistance(mesh, options);
    state.counters["grid_nodes"] = static_cast<double>(sdf.values.size());
  }
}

}  // namespace

BENCHMARK(PrepWhole)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(ImportAndValidate)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(SurfaceNodesStage)->Args({1, 1})->Args({1, 0})->Args({2, 1})->Args({2, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(SignedDistanceStage)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

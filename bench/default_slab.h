#pragma once
// The default slab of the benchmarks: 7 x 7 planar TIS blocks of the bundled default block, pitch
// 10 mm, outer ring fixed, at the paper's resolution (0.25 mm voxels, 0.6 mm nodes), built in
// memory as `tessera tile` builds it (its span L = 50 mm, M = 6 included); or n x n of them.
#include "levelset/slab_plan.h"
#include "levelset/tiler.h"

namespace tessera::bench {

inline Bundle defaultSlab(int blocksPerSide = 7) {
  SquareGridOptions grid;
  grid.columns = grid.rows = blocksPerSide;
  const SlabPlan plan = gridSlabPlan(TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj", "mm", grid);
  PrepLog log;
  Bundle slab = tileAssembly(plan.shapes, plan.placements, plan.unit, ShapeResolution{}, log);
  slab.spanLength = plan.spanLength;
  slab.spanInterfaces = plan.spanInterfaces;
  return slab;
}

}  // namespace tessera::bench

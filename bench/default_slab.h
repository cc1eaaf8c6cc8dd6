#pragma once
// The default slab of the benchmarks (DESIGN §6): 7 x 7 planar TIS blocks of the bundled default
// block, pitch 10 mm, outer ring fixed, at the paper's resolution (0.25 mm voxels, 0.6 mm nodes),
// built in memory as `tessera tile` would.
#include "geometry/tessellation.h"
#include "levelset/tiler.h"

namespace tessera::bench {

inline Bundle defaultSlab() {
  LayoutShape shape;
  shape.key = "planar";
  shape.mesh = TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj";
  PrepLog log;
  return tileAssembly({shape}, squareGrid(SquareGridOptions{}, "planar"), "mm", ShapeResolution{}, log);
}

}  // namespace tessera::bench

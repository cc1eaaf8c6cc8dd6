#pragma once
#include "geometry/tessellation.h"
#include "levelset/layout_file.h"
#include "levelset/tiler.h"

#include <string>
#include <vector>

namespace tessera {

/// What to tile: the shapes, where each body goes, the meshes' unit and the span (M, L) of
/// k_n = E M / L. Made from a block and a square grid, or read from a layout file; tileAssembly
/// turns it into a bundle.
struct SlabPlan {
  std::vector<LayoutShape> shapes;
  std::vector<Placement> placements;
  std::string unit;       ///< length unit of the meshes (and of the layout)
  std::string up = "z";   ///< the meshes' up axis, turned into +z when they are prepared
  double spanLength = 0;  ///< m, L (0: none)
  int spanInterfaces = 0; ///< M
  std::vector<std::string> notes;  ///< for the user (e.g. the block is not centred at its origin)
};

/// A square grid of one block mesh (in `unit`, its up axis `up` turned into +z; grid.pitch and
/// grid.gap in m). Blocks are laid out (and turned) about the centre of the block's plan bounding
/// box, wherever the mesh has its origin: a block with its origin at a corner still gives a
/// centred slab.
SlabPlan gridSlabPlan(const std::string& block, const std::string& unit, const SquareGridOptions& grid,
                      const std::string& up = "z");

/// The plan of a layout file (docs/tiling.md). InputError if it places more than `maxBodies`.
SlabPlan layoutSlabPlan(const std::string& layoutFile, long maxBodies);

/// The bundle of a plan: its shapes prepared at `resolution` within `limits` and its bodies placed
/// (tileAssembly), with the plan's span. What `tessera tile` and Python's tile() both write, after
/// checkAssemblyBeforeWriting.
Bundle tileSlab(const SlabPlan& plan, const ShapeResolution& resolution, PrepLog& log, const ShapeLimits& limits = {});

}  // namespace tessera

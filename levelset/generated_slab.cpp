#include "levelset/generated_slab.h"

#include "geometry/tilted_blocks.h"
#include "io/input_error.h"

#include <algorithm>
#include <cmath>

namespace tessera {

std::vector<AssemblyPart> generatedSlabParts(const GeneratedSlabOptions& options) {
  const PlaneTiling tiling = options.tilingFile.empty() ? makeTiling(options.tiling)
                                                        : readTilingFile(options.tilingFile, options.metresPerUnit, options.up);
  double size = 0;  // the tiling's extent
  for (const auto& tile : tiling.tiles)
    for (const Eigen::Vector2d& x : tile) size = std::max(size, x.norm());
  const auto across = edgeNeighbours(tiling, 1e-7 * size);
  const auto tilts = interlockingTilts(tiling, across);
  const auto cuts = cornerCuts(tiling, across, tilts, options.thickness, options.angle);
  const std::string label = options.tilingFile.empty() ? options.tiling.kind + " tiling" : options.tilingFile;
  std::vector<AssemblyPart> parts;
  int fixed = 0;
  for (std::size_t t = 0; t < tiling.tiles.size(); ++t) {
    AssemblyPart part;
    part.name = tiling.names[t];
    part.label = label + ", tile " + part.name;
    part.mesh = tiltedBlock(tiling.tiles[t], tilts[t], cuts[t], options.thickness, options.angle, options.surface);
    part.fixed = options.fixPerimeter &&
                 std::any_of(across[t].begin(), across[t].end(), [](const EdgeNeighbour& e) { return e.tile < 0; });
    fixed += part.fixed;
    parts.push_back(std::move(part));
  }
  if (options.fixPerimeter && fixed == static_cast<int>(parts.size()))
    throw InputError(label + ": every tile lies on the perimeter, so every block would be fixed; give a larger --grid");
  return parts;
}

Bundle generatedSlab(const GeneratedSlabOptions& options, const std::string& unit, const ShapeResolution& resolution,
                     const ShapeLimits& limits, PrepLog& log, AssembleReport& report) {
  AssembleOptions assemble;
  assemble.unit = unit;
  assemble.resolution = resolution;
  assemble.limits = limits;
  // Generated blocks equal up to a rigid motion are built alike to rounding: share nothing looser
  // (on a surface, neighbouring tiles differ by less than an export's rounding).
  assemble.sameShapeTolerance = 1e-9;
  return assembleParts(generatedSlabParts(options), assemble, log, report);
}

}  // namespace tessera

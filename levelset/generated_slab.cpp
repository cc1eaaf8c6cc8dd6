#include "levelset/generated_slab.h"

#include "geometry/tilted_blocks.h"
#include "io/input_error.h"
#include "levelset/interlocking_signs.h"

#include <algorithm>
#include <cmath>

namespace tessera {

std::vector<AssemblyPart> generatedSlabParts(const GeneratedSlabOptions& options, PrepLog* log) {
  const PlaneTiling tiling = options.tilingFile.empty() ? makeTiling(options.tiling)
                                                        : readTilingFile(options.tilingFile, options.metresPerUnit, options.up);
  double size = 0;  // the tiling's extent
  for (const auto& tile : tiling.tiles)
    for (const Eigen::Vector2d& x : tile) size = std::max(size, x.norm());
  const auto across = edgeNeighbours(tiling, 1e-7 * size);
  auto tilts = interlockingTilts(tiling, across, options.angle);
  std::vector<char> fixed(tiling.tiles.size());
  for (std::size_t t = 0; t < fixed.size(); ++t) fixed[t] = options.fixPerimeter && !freeTile(across[t]);
  const std::string label = options.tilingFile.empty() ? options.tiling.kind + " tiling" : options.tilingFile;
  if (options.fixPerimeter && std::all_of(fixed.begin(), fixed.end(), [](char f) { return f != 0; }))
    throw InputError(label + ": every tile lies on the perimeter, so every block would be fixed; give a larger --grid");
  // Signs that interlock the slab where the rule's do not (odd cells; curved faces).
  {
    const InterlockingSearch search = interlockSigns(tiling, across, fixed, options.thickness, options.angle, options.surface, tilts);
    const std::string programs = std::to_string(search.programs) + " interlocking program" + (search.programs == 1 ? "" : "s");
    if (log && search.flips > 0)
      log->notes.push_back("signs: " + std::to_string(search.flips) + " edges flipped from the alternating rule so that the slab interlocks (" +
                           programs + "; docs/tiling.md, \"The sign rule\")");
    if (log && search.tooLarge)
      log->notes.push_back("signs: the alternating rule's, not searched further (" + std::to_string(tiling.tiles.size()) + " tiles, over " +
                           std::to_string(InterlockingSearch::kMaxTiles) + "); tessera check says whether they interlock");
    if (log && !search.interlocked && search.programs > 0)
      log->notes.push_back("signs: the search found no flips of the alternating rule that interlock this slab (" + programs +
                           "); its signs kept (docs/tiling.md, \"The sign rule\")");
  }
  const auto cuts = cornerCuts(tiling, across, tilts, options.thickness, options.angle);
  std::vector<AssemblyPart> parts;
  for (std::size_t t = 0; t < tiling.tiles.size(); ++t) {
    AssemblyPart part;
    part.name = tiling.names[t];
    part.label = label + ", tile " + part.name;
    part.mesh = tiltedBlock(tiling.tiles[t], tilts[t], cuts[t], options.thickness, tileEdgeAngles(tiling, t, options.angle), options.surface);
    part.fixed = fixed[t] != 0;
    parts.push_back(std::move(part));
  }
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
  return assembleParts(generatedSlabParts(options, &log), assemble, log, report);
}

}  // namespace tessera

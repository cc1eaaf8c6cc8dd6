#pragma once
#include "geometry/base_surface.h"
#include "geometry/plane_tiling.h"
#include "levelset/assembler.h"

#include <string>
#include <vector>

namespace tessera {

/// A slab generated from a tiling (docs/tiling.md, "Generated tilings"): each tile becomes a
/// convex block of thickness h whose faces lean by theta, with the signs of interlockingTilts, on
/// the base surface.
struct GeneratedSlabOptions {
  TilingOptions tiling;        ///< a built-in tiling, unless tilingFile is given
  std::string tilingFile;      ///< a polygon mesh of the tiles (in `unit`)
  double metresPerUnit = 1;    ///< of tilingFile
  std::string up = "z";        ///< tilingFile's up axis, turned into +z (a surface mesh's: BaseSurface's own)
  double thickness = 0;        ///< m, h
  double angle = 0;            ///< radians, theta
  BaseSurface surface;         ///< the tiles lifted onto it (a dome, a barrel vault)
  bool fixPerimeter = true;    ///< fix the tiles with an edge on the tiling's boundary
};

/// The blocks in place, as parts to assemble (assembleParts). Throws InputError for parameters
/// that give no block, and when `fixPerimeter` fixes every tile (too small a grid).
/// The signs are searched further so that the slab interlocks (interlockSigns); what the search
/// did is noted in `log`, if given.
std::vector<AssemblyPart> generatedSlabParts(const GeneratedSlabOptions& options, PrepLog* log = nullptr);

/// The bundle of a generated slab: its parts assembled (assembleParts, `unit` recorded as the
/// shapes' source unit), blocks equal up to a rigid motion to rounding (1e-9 of their size) sharing
/// a shape, the span estimated (report.spanRule). What `tessera tile --tiling` and Python's
/// tile_tiling() write, after checkAssemblyBeforeWriting.
Bundle generatedSlab(const GeneratedSlabOptions& options, const std::string& unit, const ShapeResolution& resolution,
                     const ShapeLimits& limits, PrepLog& log, AssembleReport& report);

}  // namespace tessera

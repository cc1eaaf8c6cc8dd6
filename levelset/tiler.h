#pragma once
#include "levelset/bundle.h"
#include "levelset/layout_file.h"
#include "levelset/shape_builder.h"

#include <string>
#include <vector>

namespace tessera {

/// Builds the bundle of an assembly: each distinct shape prepared once (from its mesh file, in
/// `meshUnit` with its up axis `meshUp` turned into +z, recorded as the bundle's sourceUp, at
/// `resolution` unless the shape overrides it) or copied from an existing bundle,
/// and one body per placement, posed by placeBody. Throws InputError for a placement naming an
/// unknown shape or a shape that cannot be prepared.
Bundle tileAssembly(const std::vector<LayoutShape>& shapes, const std::vector<Placement>& placements,
                    const std::string& meshUnit, const ShapeResolution& resolution, PrepLog& log,
                    const ShapeLimits& limits = {}, const std::string& meshUp = "z");

}  // namespace tessera

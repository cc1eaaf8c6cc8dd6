#pragma once
#include "levelset/shape_builder.h"

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace tessera::tools {

/// The resolution options shared by prep, tile and assemble.
struct ResolutionArguments {
  std::optional<double> voxel;    ///< in --unit; absent: relative to each shape
  std::optional<double> spacing;  ///< in --unit; absent: relative to each shape
  double edgeSpacing = ShapeResolution{}.edgeSpacingFraction;  ///< of the spacing, at sharp edges
  double sizeGradient = ShapeResolution{}.sizeGradient;        ///< growth of the spacing away from them
  double maxMemoryGB = 4;         ///< per shape
  bool anySize = false;
};

/// --voxel, --spacing, --edge-spacing, --size-gradient, --max-memory, --any-size.
void addResolutionOptions(CLI::App& cmd, ResolutionArguments& arguments);

/// The resolution those options set (absent: relative to each shape); InputError for values out
/// of range, naming `label`.
ShapeResolution shapeResolution(const ResolutionArguments& arguments, double metresPerUnit, const std::string& label);

/// The limits those options set.
ShapeLimits shapeLimits(const ResolutionArguments& arguments);

}  // namespace tessera::tools

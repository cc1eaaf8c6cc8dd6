#pragma once
#include "levelset/shape_builder.h"

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace tessera::tools {

/// The resolution options shared by prep and tile: --voxel, --spacing (absolute, in --unit;
/// default relative to each shape), --max-memory (GB per shape) and --any-size.
void addResolutionOptions(CLI::App& cmd, std::optional<double>& voxel, std::optional<double>& spacing,
                          double& maxMemoryGB, bool& anySize);

/// The resolution those options set (absent: relative to each shape); InputError for values that
/// are not positive, naming `label`.
ShapeResolution shapeResolution(std::optional<double> voxel, std::optional<double> spacing, double metresPerUnit,
                                const std::string& label);

/// The limits those options set.
ShapeLimits shapeLimits(double maxMemoryGB, bool anySize);

}  // namespace tessera::tools

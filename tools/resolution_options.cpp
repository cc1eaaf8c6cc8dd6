#include "tools/resolution_options.h"

#include "io/input_error.h"

#include <cmath>
#include <string>

namespace tessera::tools {

void addResolutionOptions(CLI::App& cmd, ResolutionArguments& a) {
  cmd.add_option("--voxel", a.voxel,
                 "Signed-distance voxel size, in --unit [default: the shape's thinnest extent / 12.7, 0.25 mm on the paper's block]");
  cmd.add_option("--spacing", a.spacing,
                 "Surface node spacing on face interiors, in --unit [default: the shape's thinnest extent / 5.3, 0.6 mm on "
                 "the paper's block]");
  cmd.add_option("--edge-spacing", a.edgeSpacing,
                 "Node spacing along sharp edges and at corners, as a fraction of --spacing (1: uniform nodes)")
      ->capture_default_str();
  cmd.add_option("--size-gradient", a.sizeGradient,
                 "Growth of the node spacing per unit distance from a sharp edge, up to --spacing")
      ->capture_default_str();
  cmd.add_option("--max-memory", a.maxMemoryGB, "Refuse a shape whose estimated preparation needs more memory, GB")
      ->capture_default_str();
  cmd.add_flag("--any-size", a.anySize,
               "Accept blocks outside 1 mm to 10 m across (refused otherwise: a wrong --unit); the voxel must still be "
               "at least 0.01 mm, so blocks thinner than 0.13 mm need an explicit --voxel");
}

ShapeResolution shapeResolution(const ResolutionArguments& a, double metresPerUnit, const std::string& label) {
  const auto positive = [&](const char* option, double value) {
    if (!(value > 0) || !std::isfinite(value))
      throw InputError(label + ": " + option + " must be positive (got " + std::to_string(value) + ")");
  };
  ShapeResolution r;
  if (a.voxel) {
    positive("--voxel", *a.voxel);
    r.voxelSize = *a.voxel * metresPerUnit;
  }
  if (a.spacing) {
    positive("--spacing", *a.spacing);
    r.nodeSpacing = *a.spacing * metresPerUnit;
  }
  if (!validEdgeSpacingFraction(a.edgeSpacing))
    throw InputError(label + ": --edge-spacing must be between 0.05 and 1, a fraction of --spacing (got " +
                     std::to_string(a.edgeSpacing) + "); 1 gives uniform nodes");
  if (!validSizeGradient(a.sizeGradient))
    throw InputError(label + ": --size-gradient must be between 0.05 and 100 (got " + std::to_string(a.sizeGradient) + ")");
  r.edgeSpacingFraction = a.edgeSpacing;
  r.sizeGradient = a.sizeGradient;
  return r;
}

ShapeLimits shapeLimits(const ResolutionArguments& a) {
  if (!(a.maxMemoryGB > 0)) throw InputError("--max-memory must be positive (GB)");
  ShapeLimits limits;
  limits.maxMemoryBytes = a.maxMemoryGB * 1e9;
  limits.anySize = a.anySize;
  return limits;
}

}  // namespace tessera::tools

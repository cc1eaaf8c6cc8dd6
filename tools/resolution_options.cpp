#include "tools/resolution_options.h"

#include "io/input_error.h"

#include <cmath>
#include <string>

namespace tessera::tools {

void addResolutionOptions(CLI::App& cmd, std::optional<double>& voxel, std::optional<double>& spacing,
                          double& maxMemoryGB, bool& anySize) {
  cmd.add_option("--voxel", voxel,
                 "Signed-distance voxel size, in --unit [default: the shape's thinnest extent / 12.7, 0.25 mm on the paper's block]");
  cmd.add_option("--spacing", spacing,
                 "Surface node spacing, in --unit [default: the shape's thinnest extent / 5.3, 0.6 mm on the paper's block]");
  cmd.add_option("--max-memory", maxMemoryGB, "Refuse a shape whose estimated preparation needs more memory, GB")
      ->capture_default_str();
  cmd.add_flag("--any-size", anySize,
               "Accept blocks outside 1 mm to 10 m across (refused otherwise: a wrong --unit); the voxel must still be "
               "at least 0.01 mm, so blocks thinner than 0.13 mm need an explicit --voxel");
}

ShapeResolution shapeResolution(std::optional<double> voxel, std::optional<double> spacing, double metresPerUnit,
                                const std::string& label) {
  const auto positive = [&](const char* option, double value) {
    if (!(value > 0) || !std::isfinite(value))
      throw InputError(label + ": " + option + " must be positive (got " + std::to_string(value) + ")");
  };
  ShapeResolution r;
  if (voxel) {
    positive("--voxel", *voxel);
    r.voxelSize = *voxel * metresPerUnit;
  }
  if (spacing) {
    positive("--spacing", *spacing);
    r.nodeSpacing = *spacing * metresPerUnit;
  }
  return r;
}

ShapeLimits shapeLimits(double maxMemoryGB, bool anySize) {
  if (!(maxMemoryGB > 0)) throw InputError("--max-memory must be positive (GB)");
  ShapeLimits limits;
  limits.maxMemoryBytes = maxMemoryGB * 1e9;
  limits.anySize = anySize;
  return limits;
}

}  // namespace tessera::tools

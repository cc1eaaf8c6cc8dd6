#pragma once
#include "geometry/tessellation.h"

#include <optional>
#include <string>
#include <vector>

namespace tessera {

/// Where a layout's shape comes from: a mesh file to prepare, or a shape already in a bundle.
struct LayoutShape {
  std::string key;                 ///< name used by the bodies (and in the bundle)
  std::string mesh;                ///< mesh file (resolved against the layout's folder), or empty
  std::string bundle;              ///< bundle directory (resolved likewise), or empty
  std::string bundleShape;         ///< shape name inside `bundle` [default: key]
  std::optional<double> voxel;     ///< m, overrides the tile command's voxel for this shape
  std::optional<double> spacing;   ///< m, overrides the tile command's spacing
};

/// A layout file: arbitrary placements of shapes (docs/tiling.md, "Layout files").
struct Layout {
  std::string unit = "mm";             ///< unit of every length in the file
  std::vector<LayoutShape> shapes;
  std::vector<Placement> bodies;       ///< translations in metres once read
  double spanLength = 0.0;             ///< m, optional "span": {"length": L, "interfaces": M}
  int spanInterfaces = 0;
};

/// Reads a JSON layout; every problem (syntax, unknown key, missing field, unknown shape,
/// duplicate name, NaN, non-unit quaternion, empty body list) is an InputError naming the file
/// and the body or key.
Layout readLayout(const std::string& path);

/// Writes a layout (lengths in layout.unit, 17 significant digits, so poses survive a round trip).
/// Paths are written as given.
void writeLayout(const std::string& path, const Layout& layout);

}  // namespace tessera

#pragma once
#include "geometry/tessellation.h"
#include "levelset/body.h"
#include "levelset/shape.h"

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace tessera {

/// The asset bundle: a directory holding bundle.h5 (everything the solver needs) and one
/// <shape>.vdb per shape (the same grid for other tools). Schema: docs/bundle.md.
inline constexpr const char* kBundleFormatName = "tessera-bundle";
inline constexpr int kBundleFormatVersion = 1;
inline constexpr const char* kBundleFileName = "bundle.h5";

struct Bundle {
  std::string generator;        ///< tool and version that wrote it
  std::vector<Shape> shapes;
  std::vector<Body> bodies;
  /// The interlocking span of the slab, when the tessellation defines one (k_n = E M / L,
  /// Feldfogel et al.): L, the free span (m), and M, the interfaces across it; 0 when unknown.
  double spanLength = 0.0;
  int spanInterfaces = 0;
  /// The up axis of the files the bundle was built from ("x", "y", "z"); the bundle itself is
  /// always z-up (gravity along -z, the indenter moving down): other axes were turned into +z.
  std::string sourceUp = "z";

  /// Index of the shape with this name, or -1.
  int findShape(const std::string& name) const;
};

/// Reads a bundle directory (or the bundle.h5 inside it). Throws InputError naming the file for
/// a missing or corrupt bundle and for an unknown format version.
Bundle readBundle(const std::string& path);

/// Writes the bundle into `directory` (created if needed): each <shape>.vdb, then bundle.h5,
/// each to a temporary name renamed on success, so a failure leaves the previous bundle intact
/// (and removes the directory again if this call created it).
void writeBundle(const std::string& directory, const Bundle& bundle);

/// The generator string of this build ("tessera 0.1.0").
std::string generatorVersion();

}  // namespace tessera

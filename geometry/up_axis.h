#pragma once
#include <Eigen/Core>
#include <string>

namespace tessera {

/// The rotation that turns a file's up axis into +z, the solver's up (gravity along -z, the
/// indenter moving down): "z" is the identity, "y" (most design tools and game engines) turns
/// +y into +z about x, "x" turns +x into +z about y. Proper rotations: handedness is kept.
/// Throws InputError for any other name.
Eigen::Matrix3d rotationToZUp(const std::string& up);

}  // namespace tessera

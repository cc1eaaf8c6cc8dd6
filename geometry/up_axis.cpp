#include "geometry/up_axis.h"

#include "io/input_error.h"

namespace tessera {

Eigen::Matrix3d rotationToZUp(const std::string& up) {
  Eigen::Matrix3d r;
  if (up == "z") r.setIdentity();
  else if (up == "y") r << 1, 0, 0, 0, 0, -1, 0, 1, 0;   // (x, y, z) -> (x, -z, y)
  else if (up == "x") r << 0, 0, -1, 0, 1, 0, 1, 0, 0;   // (x, y, z) -> (-z, y, x)
  else throw InputError("up axis '" + up + "': give the file's up axis as x, y or z");
  return r;
}

}  // namespace tessera

#pragma once
#include <Eigen/Geometry>
#include <string>

namespace tessera {

/// A placed block: a shape at a pose.
struct Body {
  std::string name;                                             ///< e.g. "r3c4"
  int shape = 0;                                                ///< index into the shapes it is placed among (Bundle::shapes)
  Eigen::Vector3d position{0, 0, 0};                            ///< m, world position of the body-frame origin
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< unit; body frame -> world
  bool fixed = false;                                           ///< boundary block: never moves
};

}  // namespace tessera

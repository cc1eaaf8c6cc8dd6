#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace tessera {

/// Where one block goes: its mesh frame is placed by x_world = rotation * x_mesh + translation.
/// (The tiler turns this into the body pose of the block's principal frame.)
struct Placement {
  std::string name;                                          ///< unique body name
  std::string shape;                                         ///< key of the block's shape
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< unit
  Eigen::Vector3d translation{0, 0, 0};                      ///< m
  bool fixed = false;                                        ///< boundary block: never moves
};

struct SquareGridOptions {
  int columns = 7;              ///< blocks along x
  int rows = 7;                 ///< blocks along y
  double pitch = 10e-3;         ///< m, centre-to-centre distance of neighbours
  double gap = 0.0;             ///< m, clearance added to the pitch
  bool alternate = true;        ///< turn every other block 90 degrees about z (checkerboard): interlocking TIS
  bool fixPerimeter = true;     ///< fix the outer ring
};

/// A rows x columns square tessellation centred at the origin in the plane z = 0. Block (c, r) is
/// named "r<r>c<c>", sits at ((c - (columns-1)/2) p, (r - (rows-1)/2) p, 0) with p = pitch + gap,
/// and is turned 90 degrees about z when (r + c) is odd and `alternate` is set.
std::vector<Placement> squareGrid(const SquareGridOptions& options, const std::string& shape);

/// The interlocking span of a square grid with its perimeter fixed (Feldfogel et al.): the free
/// span L = (n - 2) pitch and M = n - 1 interfaces across it, along the shorter side n.
struct InterlockingSpan {
  double length = 0.0;  ///< L, m
  int interfaces = 0;   ///< M
};
InterlockingSpan squareGridSpan(const SquareGridOptions& options);

}  // namespace tessera

#pragma once
#include "levelset/bundle.h"

#include <string>

namespace tessera {

/// What exportAssembly wrote.
struct ExportSummary {
  std::size_t triangles = 0;  ///< cells of blocks.vtu
  std::size_t nodes = 0;      ///< points of nodes.vtu
};

/// Writes a bundle's assembly for ParaView into `directory`:
///  - blocks.vtu: every body's mesh placed by its pose (triangles; cell data body_id, shape_id, fixed);
///  - nodes.vtu: every body's surface nodes in world coordinates (vertex cells; point data
///    body_id, area, normal, kind);
///  - assembly.pvd: a collection of the two (open this one);
///  - layout.json: the placements as a layout file whose shapes refer to the bundle, so
///    `tessera tile --layout layout.json` rebuilds the same assembly.
/// Lengths in metres. Each file is written to a temporary name and renamed.
ExportSummary exportAssembly(const Bundle& bundle, const std::string& bundlePath, const std::string& directory);

/// Writes blocks.vtu-style triangles of every body at the given poses (body centroid position
/// and orientation per body, as in Bundle::bodies) to `path`; returns the triangle count. Cell
/// data body_id, shape_id, fixed and, per body, each of `bodyVectors` (e.g. displacement, m, and
/// velocity, m/s); field data body_names. Arrays appended as raw binary.
std::size_t writeBlocksVtu(const Bundle& bundle, const std::vector<Eigen::Vector3d>& position,
                           const std::vector<Eigen::Quaterniond>& orientation, const std::string& path,
                           const std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>>& bodyVectors = {});

/// Writes a sphere (triangles) of `radius` at `centre` (m) to `path`: the indenter in a series.
void writeSphereVtu(const Eigen::Vector3d& centre, double radius, const std::string& path);

/// Writes a ParaView collection (.pvd) of `files` (relative to the .pvd) at the given times; files
/// at the same time become parts 0, 1, ... of that time step.
void writePvd(const std::string& path, const std::vector<std::string>& files, const std::vector<double>& times);

/// Writes points as VTK vertex cells with named point-data vectors and scalars (m, any units).
void writePointsVtu(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                    const std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>>& vectors,
                    const std::vector<std::pair<std::string, std::vector<double>>>& scalars);

}  // namespace tessera

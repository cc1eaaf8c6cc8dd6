#pragma once
#include "geometry/triangle_mesh.h"
#include "levelset/dense_sdf.h"
#include "io/safe_write.h"

#include <string>

namespace tessera {

struct SignedDistanceOptions {
  double voxelSize = 0.25e-3;  ///< m
  int exteriorBandVoxels = 3;  ///< exact distances this many voxels outside the surface; the grid is padded as much
};

/// The signed distance to a closed, outward-oriented mesh on the nodes of a grid covering the
/// mesh's bounding box padded by the exterior band. The sign comes from OpenVDB
/// (tools::meshToSignedDistanceField, interior filled); the magnitude at every node, inside and
/// out, is the exact distance to the polyhedron (CGAL AABB tree). `background` is the band width.
DenseSdf buildSignedDistance(const TriangleMesh& mesh, const SignedDistanceOptions& options);

/// Writes the field as an OpenVDB level-set grid named `gridName` (viewable in ParaView,
/// Houdini, Blender). Metadata records the unit (m). Added to `files`: written to a temporary file,
/// read back, and renamed with the set's other files.
void writeVdb(FileSetWriter& files, const DenseSdf& sdf, const std::string& path, const std::string& gridName);

/// Reads the grid named `gridName` back into a dense field over the given grid's layout
/// (origin, dims, voxel size of `layout`). Throws InputError if the file or grid is missing.
DenseSdf readVdb(const std::string& path, const std::string& gridName, const DenseSdf& layout);

}  // namespace tessera

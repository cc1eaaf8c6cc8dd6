#include "levelset/shape.h"

#include "levelset/mesh_sdf_builder.h"

#include <cstdio>

namespace tessera {

MeshSdf exactMeshLevelSet(const Shape& shape) {
  return buildMeshSdf(shape.mesh, shape.sdf, kExactMeshBandVoxels * shape.sdf.voxelSize);
}

void deriveExactMesh(Shape& shape) { shape.exactMesh = exactMeshLevelSet(shape); }

std::string levelSetPath(const Shape& shape, bool exactConvexLevelSets, bool exactMeshLevelSets) {
  char buffer[96];
  if (!shape.convex || !exactConvexLevelSets) {
    if (!exactMeshLevelSets || shape.exactMesh.empty())
      return shape.convex ? "grid (exact planes and mesh off)" : "grid (not convex; exact mesh off)";
    std::snprintf(buffer, sizeof buffer, "exact mesh (%zu triangles%s)", shape.exactMesh.triangles.size(),
                  shape.convex ? "; exact planes off" : ", not convex");
    return buffer;
  }
  std::snprintf(buffer, sizeof buffer, "exact planes (%zu faces, convex to %.2g mm)", shape.convex->planes.size(),
                shape.convex->deviation * 1e3);
  return buffer;
}

}  // namespace tessera

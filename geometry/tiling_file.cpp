// readTilingFile: a tiling drawn in a design tool, as a polygon mesh.
#include "geometry/plane_tiling.h"

#include "geometry/up_axis.h"
#include "io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <filesystem>

namespace tessera {

namespace {

// True when every turn of the counter-clockwise polygon is to the left (collinear corners allowed).
bool isConvex(const std::vector<Eigen::Vector2d>& p, double tolerance) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d a = p[(i + 1) % p.size()] - p[i], b = p[(i + 2) % p.size()] - p[(i + 1) % p.size()];
    if (a.x() * b.y() - a.y() * b.x() < -tolerance * a.norm() * b.norm()) return false;
  }
  return true;
}

}  // namespace

PlaneTiling readTilingFile(const std::string& path, double metresPerUnit, const std::string& up) {
  const Eigen::Matrix3d toZUp = rotationToZUp(up);
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path + ": no such tiling file; give a polygon mesh (OBJ) of the tiles, or a built-in tiling name");
  Assimp::Importer importer;
  // Polygons are kept as they are (no triangulation): each face is one tile.
  const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure | aiProcess_PreTransformVertices);
  if (scene == nullptr)
    throw InputError(path + ": cannot read as a polygon mesh (" + std::string(importer.GetErrorString()) + "); give an OBJ of the tiles");
  PlaneTiling tiling;
  double lowest = 1e300, highest = -1e300, size = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines are not tiles
      std::vector<Eigen::Vector2d> tile;
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices)
          throw InputError(path + ": face " + std::to_string(f) + " names a vertex that is not there; export the tiling again");
        const aiVector3D& read = mesh->mVertices[face.mIndices[k]];
        const Eigen::Vector3d v = toZUp * Eigen::Vector3d(read.x, read.y, read.z) * metresPerUnit;
        tile.emplace_back(v.x(), v.y());
        lowest = std::min(lowest, v.z());
        highest = std::max(highest, v.z());
      }
      if (polygonArea(tile) < 0) std::reverse(tile.begin(), tile.end());
      tiling.names.push_back("t" + std::to_string(tiling.tiles.size()));
      tiling.tiles.push_back(std::move(tile));
    }
  }
  if (tiling.tiles.empty()) throw InputError(path + ": holds no polygon; give an OBJ whose faces are the tiles");
  for (const auto& tile : tiling.tiles)
    for (const Eigen::Vector2d& x : tile) size = std::max(size, x.norm());
  if (highest - lowest > 1e-6 * size)
    throw InputError(path + ": the tiles do not lie in one plane normal to the up axis " + up + " (they span " +
                     std::to_string((highest - lowest) / metresPerUnit) + " along it); give a flat tiling, and --up for a y-up file");
  for (std::size_t t = 0; t < tiling.tiles.size(); ++t) {
    const double area = polygonArea(tiling.tiles[t]);
    if (!(area > 1e-12 * size * size))
      throw InputError(path + ": face " + std::to_string(t) + " has no area; remove it or export the tiling again");
    if (!isConvex(tiling.tiles[t], 1e-9))
      throw InputError(path + ": face " + std::to_string(t) + " is not convex; split it into convex tiles");
  }
  return tiling;
}

}  // namespace tessera

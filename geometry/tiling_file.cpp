// readTilingFile: a tiling drawn in a design tool, as a polygon mesh.
#include "geometry/plane_tiling.h"

#include "geometry/up_axis.h"
#include "io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>

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

// A group's face angle from its name, `angle_<degrees>`: NaN for any other name.
double groupAngle(const std::string& path, const std::string& name) {
  const std::string prefix = "angle_";
  if (name.compare(0, prefix.size(), prefix) != 0) return std::nan("");
  const std::string number = name.substr(prefix.size());
  char* end = nullptr;
  const double degrees = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size())
    throw InputError(path + ": group '" + name + "' names no angle; name a group of edges angle_<degrees>, e.g. angle_7.5");
  if (!(degrees >= 0 && degrees < 90))
    throw InputError(path + ": group '" + name + "': give the faces' tilt in degrees, in [0, 90)");
  return degrees * M_PI / 180;
}

struct AngledSegment {
  Eigen::Vector2d a, b;
  double angle;      // radians
  std::string group;
};

// Each segment's angle given to the tile edges it lies on, end to end (both tiles of a shared edge).
void giveEdgeAngles(const std::string& path, const std::vector<AngledSegment>& segments, double tolerance, double metresPerUnit,
                    PlaneTiling& tiling) {
  if (segments.empty()) return;
  tiling.edgeAngles.assign(tiling.tiles.size(), {});
  std::vector<std::vector<const AngledSegment*>> givenBy(tiling.tiles.size());
  for (std::size_t t = 0; t < tiling.tiles.size(); ++t) {
    tiling.edgeAngles[t].assign(tiling.tiles[t].size(), std::nan(""));
    givenBy[t].assign(tiling.tiles[t].size(), nullptr);
  }
  for (const AngledSegment& segment : segments) {
    bool found = false;
    for (std::size_t t = 0; t < tiling.tiles.size(); ++t) {
      const auto& tile = tiling.tiles[t];
      for (std::size_t k = 0; k < tile.size(); ++k) {
        const Eigen::Vector2d &p = tile[k], &q = tile[(k + 1) % tile.size()];
        const bool along = (p - segment.a).norm() <= tolerance && (q - segment.b).norm() <= tolerance;
        const bool against = (p - segment.b).norm() <= tolerance && (q - segment.a).norm() <= tolerance;
        if (!along && !against) continue;
        if (givenBy[t][k] && givenBy[t][k]->angle != segment.angle)
          throw InputError(path + ": an edge of tile " + tiling.names[t] + " is in groups '" + givenBy[t][k]->group + "' and '" +
                           segment.group + "'; give each edge one angle");
        tiling.edgeAngles[t][k] = segment.angle;
        givenBy[t][k] = &segment;
        found = true;
      }
    }
    if (!found) {
      const auto at = [&](const Eigen::Vector2d& x) {
        return "(" + std::to_string(x.x() / metresPerUnit) + ", " + std::to_string(x.y() / metresPerUnit) + ")";
      };
      throw InputError(path + ": the line " + at(segment.a) + "-" + at(segment.b) + " of group '" + segment.group +
                       "' is no tile's edge; draw each angled edge from corner to corner of its tiles");
    }
  }
}

}  // namespace

PlaneTiling readTilingFile(const std::string& path, double metresPerUnit, const std::string& up) {
  const Eigen::Matrix3d toZUp = rotationToZUp(up);
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path + ": no such tiling file; give a polygon mesh (OBJ) of the tiles, or a built-in tiling name");
  Assimp::Importer importer;
  // Polygons are kept as they are (no triangulation): each face is one tile. The nodes are walked
  // with their transforms (not pre-transformed), so that each group keeps its name.
  const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  if (scene == nullptr || scene->mRootNode == nullptr)
    throw InputError(path + ": cannot read as a polygon mesh (" + std::string(importer.GetErrorString()) + "); give an OBJ of the tiles");
  PlaneTiling tiling;
  std::vector<AngledSegment> segments;
  double lowest = 1e300, highest = -1e300, size = 0;
  const std::function<void(const aiNode*, const aiMatrix4x4&)> visit = [&](const aiNode* node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 transform = parent * node->mTransformation;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
      // An angle group is the node's name (OBJ's g or o, a design tool's object); the mesh's where
      // that names none (OBJ meshes split by material are named after it).
      std::string group = node->mName.C_Str();
      double angle = groupAngle(path, group);
      if (!std::isfinite(angle)) {
        group = mesh->mName.C_Str();
        angle = groupAngle(path, group);
      }
      const auto point = [&](unsigned index) {
        if (index >= mesh->mNumVertices)
          throw InputError(path + ": face " + std::to_string(tiling.tiles.size()) + " names a vertex that is not there; export the tiling again");
        const aiVector3D read = transform * mesh->mVertices[index];
        const Eigen::Vector3d v = toZUp * Eigen::Vector3d(read.x, read.y, read.z) * metresPerUnit;
        lowest = std::min(lowest, v.z());
        highest = std::max(highest, v.z());
        return Eigen::Vector2d(v.x(), v.y());
      };
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices == 2 && std::isfinite(angle))  // a line: an angled edge
          segments.push_back({point(face.mIndices[0]), point(face.mIndices[1]), angle, group});
        if (face.mNumIndices < 3) continue;  // points and lines are not tiles
        std::vector<Eigen::Vector2d> tile;
        for (unsigned k = 0; k < face.mNumIndices; ++k) tile.push_back(point(face.mIndices[k]));
        if (polygonArea(tile) < 0) std::reverse(tile.begin(), tile.end());
        tiling.names.push_back("t" + std::to_string(tiling.tiles.size()));
        tiling.tiles.push_back(std::move(tile));
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) visit(node->mChildren[c], transform);
  };
  visit(scene->mRootNode, aiMatrix4x4());
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
  giveEdgeAngles(path, segments, 1e-6 * size, metresPerUnit, tiling);
  return tiling;
}

}  // namespace tessera

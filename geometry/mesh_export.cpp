#include "geometry/mesh_export.h"

#include "io/input_error.h"
#include "io/safe_write.h"

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace tessera {

namespace fs = std::filesystem;

MeshFileFormat meshFormatFromPath(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".obj") return MeshFileFormat::Obj;
  if (ext == ".stl") return MeshFileFormat::StlBinary;
  throw InputError(path + ": unknown mesh extension '" + ext + "'; use .obj or .stl");
}

void writeMesh(const TriangleMesh& mesh, const std::string& path, MeshFileFormat format, double metresPerUnit) {
  if (format == MeshFileFormat::Obj) {
    // Written here, not by assimp: its OBJ exporter (5.2) rounds every coordinate to float and
    // writes normals of its own making for a mesh that has none (a planar block's top face got
    // (-0.996, 0, -0.087)). OBJ's v/f lines are the whole format. (Reading is still assimp's,
    // in float: tessera's own import keeps 7 digits; other readers get all 17.)
    std::string text = "# tessera\n";
    char line[128];
    for (const Eigen::Vector3d& v : mesh.vertices) {
      const Eigen::Vector3d p = v / metresPerUnit;
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
      text += line;
    }
    for (const auto& t : mesh.triangles)
      text += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
    writeTextFileSafely(fs::path(path), text);
    return;
  }
  // STL (single precision by its format): by assimp. aiScene's destructor frees what it owns, so
  // build it with new[] as assimp expects.
  aiScene scene;
  scene.mRootNode = new aiNode();
  scene.mRootNode->mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh*[1]{new aiMesh()};
  aiMesh* out = scene.mMeshes[0];
  out->mMaterialIndex = 0;
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out->mNumVertices = static_cast<unsigned>(mesh.vertices.size());
  out->mVertices = new aiVector3D[out->mNumVertices];
  for (unsigned v = 0; v < out->mNumVertices; ++v) {
    const Eigen::Vector3d p = mesh.vertices[v] / metresPerUnit;
    out->mVertices[v] = aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()), static_cast<ai_real>(p.z()));
  }
  out->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  out->mFaces = new aiFace[out->mNumFaces];
  for (unsigned f = 0; f < out->mNumFaces; ++f) {
    out->mFaces[f].mNumIndices = 3;
    out->mFaces[f].mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) out->mFaces[f].mIndices[k] = static_cast<unsigned>(mesh.triangles[f][k]);
  }
  const char* formatId = format == MeshFileFormat::StlAscii ? "stl" : "stlb";
  writeFileSafely(fs::path(path), [&](const fs::path& temporary) {
    Assimp::Exporter exporter;
    if (exporter.Export(&scene, formatId, temporary.string()) != AI_SUCCESS)
      throw std::runtime_error(std::string("cannot write mesh (") + exporter.GetErrorString() + ")");
  });
}

}  // namespace tessera

#include "geometry/mesh_import.h"

#include "geometry/ply_reader.h"
#include "geometry/up_axis.h"
#include "io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// STL, OBJ and the other formats assimp knows, in the file's units: polygons triangulated,
// identical vertices joined, node transforms baked in.
TriangleMesh readWithAssimp(const std::string& path) {
  Assimp::Importer importer;
  // Points and lines are not a surface: ask assimp to drop them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Only positions matter; without per-facet normals and texture coordinates, corners that STL
  // and OBJ repeat verbatim are joined on reading.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TEXCOORDS | aiComponent_COLORS |
                                                          aiComponent_TANGENTS_AND_BITANGENTS);
  const auto unreadable = [&] {
    std::string why = importer.GetErrorString();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    return InputError(path + ": cannot read as a mesh (" + why + "); give a valid STL (ASCII or binary), OBJ or PLY file");
  };
  // Read and validated first, the faces checked, then post-processed: assimp's steps assert (abort)
  // on faces its readers should have refused (a damaged PLY's face of no corner aborted in
  // Triangulate; found by fuzz_mesh_import).
  const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  if (scene == nullptr) throw unreadable();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      bool valid = face.mNumIndices > 0 && face.mIndices != nullptr;
      for (unsigned k = 0; valid && k < face.mNumIndices; ++k) valid = face.mIndices[k] < mesh->mNumVertices;
      if (!valid)
        throw InputError(path + ": face " + std::to_string(f) + " has no corners or names a vertex that is not there; " +
                         "the file is damaged, export the mesh again");
    }
  }
  scene = importer.ApplyPostProcessing(aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                       aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (scene == nullptr) throw unreadable();

  TriangleMesh out;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      out.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.triangles.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                               base + static_cast<int>(face.mIndices[2])});
    }
  }
  return out;
}

}  // namespace

ImportedMesh importMesh(const std::string& path, const MeshImportOptions& options) {
  const Eigen::Matrix3d toZUp = rotationToZUp(options.up);
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": no such file; check the path");
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": not a regular file; give a mesh file (STL, OBJ or PLY)");
  if (fs::file_size(path, ec) == 0) throw InputError(path + ": the file is empty; give a mesh file (STL, OBJ or PLY)");

  ImportedMesh out;
  if (isPlyFile(path)) {
    out.mesh = readPly(path);  // Tessera's own reader (geometry/ply_reader.h: why)
  } else {
    out.mesh = readWithAssimp(path);
  }
  for (std::size_t v = 0; v < out.mesh.vertices.size(); ++v) {
    if (!out.mesh.vertices[v].allFinite())
      throw InputError(path + ": vertex " + std::to_string(v) + " has a non-finite coordinate; repair the file");
    out.mesh.vertices[v] *= options.metresPerUnit;
  }
  if (out.mesh.triangles.empty()) throw InputError(path + ": the file holds no triangles; give a closed triangle mesh");

  out.fileVertices = out.mesh.vertices.size();
  const double diagonal = boundingBox(out.mesh.vertices).diagonal().norm();
  const double tolerance = options.weldTolerance >= 0 ? options.weldTolerance : 1e-6 * diagonal;
  const std::size_t read = out.mesh.triangles.size();
  out.weld = weldVertices(out.mesh, tolerance);
  if (out.mesh.triangles.empty())
    throw InputError(path + ": every triangle collapsed when vertices were welded (the mesh has no extent); check the file");
  if (out.mesh.triangles.size() < 4 && out.weld.collapsedTriangles > 0) {  // what is left is no solid, whatever it is
    char span[32];
    std::snprintf(span, sizeof span, "%.3g", diagonal / options.metresPerUnit);
    throw InputError(path + ": " + std::to_string(out.weld.collapsedTriangles) + " of its " + std::to_string(read) +
                     " triangles collapsed when nearby vertices were welded (it spans " + span +
                     " units of the file): its coordinates look damaged; check the file");
  }
  if (options.up != "z")
    for (Eigen::Vector3d& v : out.mesh.vertices) v = toZUp * v;
  return out;
}

}  // namespace tessera

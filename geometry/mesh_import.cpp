#include "geometry/mesh_import.h"

#include "geometry/up_axis.h"
#include "io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// Bytes a PLY property takes at least: its size in a binary file, a digit and a separator in an
// ASCII one (a list at least its count).
std::uintmax_t plyPropertyBytes(const std::string& type, bool ascii) {
  if (ascii) return 2;
  static const std::map<std::string, std::uintmax_t> sizes{
      {"char", 1},   {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},   {"ushort", 2}, {"int16", 2},
      {"uint16", 2}, {"int", 4},    {"uint", 4},   {"int32", 4},   {"uint32", 4},  {"float", 4},  {"float32", 4},
      {"double", 8}, {"float64", 8}};
  const auto found = sizes.find(type);
  return found == sizes.end() ? 1 : found->second;
}

// A PLY header's element counts against the bytes the file holds: assimp reserves memory for the
// counts the header claims, so a damaged header (2 000 000 000 vertices in a 1 kB file) grew
// memory without bound. The other formats' readers check their counts against the file.
void checkPlyCounts(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) return;
  bool ascii = false;
  std::uintmax_t needed = 0, count = 0;
  std::string element;
  const auto close = [&](std::uintmax_t bytes) {
    if (count > 0 && bytes > (std::numeric_limits<std::uintmax_t>::max() / 4) / count)
      throw InputError(path + ": its PLY header claims " + std::to_string(count) + " " + element + "s; the file is damaged");
    needed += count * bytes;
  };
  std::uintmax_t elementBytes = 0;
  for (int lines = 0; std::getline(in, line) && lines < 10000; ++lines) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> word;
      ascii = word == "ascii";
    } else if (word == "element") {
      close(elementBytes);
      elementBytes = 0;
      count = 0;
      words >> element >> count;
    } else if (word == "property") {
      words >> word;
      if (word == "list") words >> word;  // the count's type; a list holds its count at least
      elementBytes += plyPropertyBytes(word, ascii);
    } else if (word == "end_header") {
      close(elementBytes);
      const std::uintmax_t header = static_cast<std::uintmax_t>(in.tellg()), size = fs::file_size(path);
      if (needed > size - std::min(size, header))
        throw InputError(path + ": its PLY header claims more elements than the file's " + std::to_string(size) +
                         " bytes can hold (the file is truncated or its header damaged); export the mesh again");
      return;
    }
  }
  // assimp's reader loops forever on a header that never ends (found by fuzz_mesh_import).
  throw InputError(path + ": its PLY header has no end_header line (the file is truncated or damaged); export the mesh again");
}

}  // namespace

ImportedMesh importMesh(const std::string& path, const MeshImportOptions& options) {
  const Eigen::Matrix3d toZUp = rotationToZUp(options.up);
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": no such file; check the path");
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": not a regular file; give a mesh file (STL or OBJ)");
  if (fs::file_size(path, ec) == 0) throw InputError(path + ": the file is empty; give a mesh file (STL or OBJ)");

  checkPlyCounts(path);

  Assimp::Importer importer;
  // Points and lines are not a surface: ask assimp to drop them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Only positions matter; without per-facet normals and texture coordinates, corners that STL
  // and OBJ repeat verbatim are joined on reading.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TEXCOORDS | aiComponent_COLORS |
                                                          aiComponent_TANGENTS_AND_BITANGENTS);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    std::string why = importer.GetErrorString();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    throw InputError(path + ": cannot read as a mesh (" + why + "); give a valid STL (ASCII or binary) or OBJ file");
  }

  ImportedMesh out;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const int base = static_cast<int>(out.mesh.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Eigen::Vector3d x(p.x, p.y, p.z);
      if (!x.allFinite()) throw InputError(path + ": vertex " + std::to_string(v) + " has a non-finite coordinate; repair the file");
      out.mesh.vertices.push_back(x * options.metresPerUnit);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.mesh.triangles.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                                    base + static_cast<int>(face.mIndices[2])});
    }
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

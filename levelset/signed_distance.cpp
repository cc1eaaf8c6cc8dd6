// The one translation unit that includes OpenVDB (its headers are heavy to compile).
#include "levelset/signed_distance.h"

#include "io/input_error.h"
#include "geometry/point_mesh_distance.h"
#include "io/safe_write.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>

namespace tessera {

namespace {

void initializeOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

}  // namespace

DenseSdf buildSignedDistance(const TriangleMesh& mesh, const SignedDistanceOptions& options) {
  initializeOpenVdb();
  const double h = options.voxelSize;
  const auto transform = openvdb::math::Transform::createLinearTransform(h);

  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) points.emplace_back(float(v.x()), float(v.y()), float(v.z()));
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  const std::vector<openvdb::Vec4I> quads;

  // Interior band "infinite": every voxel inside gets its exact distance.
  const float exteriorBand = static_cast<float>(options.exteriorBandVoxels);
  const openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
      *transform, points, triangles, quads, exteriorBand, std::numeric_limits<float>::max());

  // Dense grid over the mesh bounding box, padded by the band, in grid index space. (The 1e-4
  // voxel slack keeps a box face lying on a grid plane from flipping the layout on rounding.)
  const Eigen::AlignedBox3d box = boundingBox(mesh.vertices);
  DenseSdf sdf;
  sdf.voxelSize = h;
  sdf.background = grid->background();
  Eigen::Array3i lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = static_cast<int>(std::floor(box.min()[a] / h + 1e-4)) - options.exteriorBandVoxels;
    hi[a] = static_cast<int>(std::ceil(box.max()[a] / h - 1e-4)) + options.exteriorBandVoxels;
    sdf.dims[a] = hi[a] - lo[a] + 1;
  }
  sdf.origin = h * lo.cast<double>().matrix();
  sdf.values.resize(static_cast<std::size_t>(sdf.dims[0]) * sdf.dims[1] * sdf.dims[2]);
  // OpenVDB's sign is robust (its inside/outside flood fill), but away from the surface its
  // interior distances are approximate (measured: up to 0.4 voxel near concave edges). Every node
  // therefore takes the exact distance to the polyhedron (CGAL AABB tree) with OpenVDB's sign.
  const PointMeshDistance exact(mesh);
  tbb::parallel_for(0, sdf.dims[0], [&](int i) {
    const auto accessor = grid->getConstAccessor();
    for (int j = 0; j < sdf.dims[1]; ++j)
      for (int k = 0; k < sdf.dims[2]; ++k) {
        const double sign = accessor.getValue(openvdb::Coord(lo[0] + i, lo[1] + j, lo[2] + k)) < 0 ? -1.0 : 1.0;
        sdf.values[sdf.index(i, j, k)] = static_cast<float>(sign * exact.distance(sdf.nodePosition(i, j, k)));
      }
  });
  return sdf;
}

namespace {

openvdb::Coord originCoord(const DenseSdf& sdf) {
  const Eigen::Vector3d o = sdf.origin / sdf.voxelSize;
  return openvdb::Coord(int(std::lround(o.x())), int(std::lround(o.y())), int(std::lround(o.z())));
}

}  // namespace

void writeVdb(FileSetWriter& files, const DenseSdf& sdf, const std::string& path, const std::string& gridName) {
  initializeOpenVdb();
  auto grid = openvdb::FloatGrid::create(sdf.background);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(sdf.voxelSize));
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  grid->setName(gridName);
  grid->insertMeta("length_unit", openvdb::StringMetadata("m"));
  const openvdb::Coord o = originCoord(sdf);
  auto accessor = grid->getAccessor();
  for (int i = 0; i < sdf.dims[0]; ++i)
    for (int j = 0; j < sdf.dims[1]; ++j)
      for (int k = 0; k < sdf.dims[2]; ++k) {
        const float v = sdf.at(i, j, k);
        if (v < sdf.background) accessor.setValue(o.offsetBy(i, j, k), v);  // all of the inside, and the band
      }

  namespace fs = std::filesystem;
  // OpenVDB does not report every failed write: the grid is read back before the rename.
  files.add(
      fs::path(path),
      [&](const fs::path& temporary) {
        openvdb::io::File file(temporary.string());
        file.write({grid});
        file.close();
      },
      [&](const fs::path& temporary) {
        openvdb::io::File file(temporary.string());
        file.open();
        if (!file.readGrid(gridName)) throw std::runtime_error("grid '" + gridName + "' missing");
        file.close();
      });
}

DenseSdf readVdb(const std::string& path, const std::string& gridName, const DenseSdf& layout) {
  initializeOpenVdb();
  openvdb::FloatGrid::Ptr grid;
  try {
    openvdb::io::File file(path);
    file.open();
    grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(gridName));
    file.close();
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot read grid '" + gridName + "' (" + e.what() + ")");
  }
  if (!grid) throw InputError(path + ": grid '" + gridName + "' is not a float grid");
  DenseSdf out = layout;
  out.background = grid->background();
  const openvdb::Coord o = originCoord(layout);
  const auto accessor = grid->getConstAccessor();
  for (int i = 0; i < out.dims[0]; ++i)
    for (int j = 0; j < out.dims[1]; ++j)
      for (int k = 0; k < out.dims[2]; ++k) out.values[out.index(i, j, k)] = accessor.getValue(o.offsetBy(i, j, k));
  return out;
}

}  // namespace tessera

#include "levelset/bundle.h"

#include "io/input_error.h"
#include "levelset/bundle_check.h"
#include "io/hdf5_file.h"
#include "levelset/signed_distance.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace tessera {

namespace fs = std::filesystem;
using h5::Handle;

#ifndef TESSERA_VERSION
#define TESSERA_VERSION "0.0.0"
#endif

std::string generatorVersion() { return std::string("tessera ") + TESSERA_VERSION; }

int Bundle::findShape(const std::string& name) const {
  for (std::size_t i = 0; i < shapes.size(); ++i)
    if (shapes[i].name == name) return static_cast<int>(i);
  return -1;
}

namespace {

// ---- flattening helpers: Eigen arrays <-> row-major vectors ----

std::vector<double> flatten(const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> out;
  out.reserve(3 * points.size());
  for (const auto& p : points) out.insert(out.end(), {p.x(), p.y(), p.z()});
  return out;
}

std::vector<Eigen::Vector3d> unflatten(const std::vector<double>& data) {
  std::vector<Eigen::Vector3d> out(data.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Eigen::Vector3d(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
  return out;
}

std::vector<double> flatten(const Eigen::Matrix3d& m) {  // row-major
  std::vector<double> out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.push_back(m(i, j));
  return out;
}

Eigen::Matrix3d matrixFrom(const std::vector<double>& data) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = data[3 * i + j];
  return m;
}

std::vector<double> flatten(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

hsize_t rows(std::size_t n) { return static_cast<hsize_t>(n); }

// ---- writing ----

void writeShape(hid_t shapes, const Shape& s, std::int64_t index) {
  Handle g = h5::createGroup(shapes, s.name);
  h5::writeAttribute(g.get(), "index", index);
  h5::writeAttribute(g.get(), "source_file", s.source.file);
  h5::writeAttribute(g.get(), "source_unit", s.source.unit);
  h5::writeAttribute(g.get(), "source_metres_per_unit", s.source.metresPerUnit);
  h5::writeAttribute(g.get(), "voxel_size", s.resolution.voxelSize);
  h5::writeAttribute(g.get(), "node_spacing", s.resolution.nodeSpacing);
  h5::writeAttribute(g.get(), "edge_spacing_fraction", s.resolution.edgeSpacingFraction);
  h5::writeAttribute(g.get(), "size_gradient", s.resolution.sizeGradient);
  h5::writeAttribute(g.get(), "feature_angle", s.resolution.featureAngle);
  h5::writeAttribute(g.get(), "exterior_band_voxels", static_cast<std::int64_t>(s.resolution.exteriorBandVoxels));
  h5::writeAttribute(g.get(), "volume", s.mass.volume);
  h5::writeAttribute(g.get(), "surface_area", s.mass.surfaceArea);
  h5::writeAttribute(g.get(), "vdb_file", s.name + ".vdb");
  h5::writeAttribute(g.get(), "level_set", levelSetPath(s));  // for readers; recomputed from the mesh on reading
  h5::writeDataset(g.get(), "centroid", flatten(s.mass.centroid), {3});
  h5::writeDataset(g.get(), "inertia", flatten(s.mass.inertia), {3, 3});
  h5::writeDataset(g.get(), "principal_moments", flatten(s.mass.principalMoments), {3});
  h5::writeDataset(g.get(), "principal_axes", flatten(s.mass.principalAxes), {3, 3});

  Handle mesh = h5::createGroup(g.get(), "mesh");
  h5::writeDataset(mesh.get(), "vertices", flatten(s.mesh.vertices), {rows(s.mesh.vertices.size()), 3});
  std::vector<std::int32_t> triangles;
  for (const auto& t : s.mesh.triangles) triangles.insert(triangles.end(), {t[0], t[1], t[2]});
  h5::writeDataset(mesh.get(), "triangles", triangles, {rows(s.mesh.triangles.size()), 3});

  Handle nodes = h5::createGroup(g.get(), "nodes");
  const hsize_t n = rows(s.nodes.size());
  h5::writeDataset(nodes.get(), "positions", flatten(s.nodes.positions), {n, 3});
  h5::writeDataset(nodes.get(), "normals", flatten(s.nodes.normals), {n, 3});
  h5::writeDataset(nodes.get(), "areas", s.nodes.areas, {n});
  h5::writeDataset(nodes.get(), "patches", std::vector<std::int32_t>(s.nodes.patches.begin(), s.nodes.patches.end()), {n});
  std::vector<std::uint8_t> kinds;
  for (NodeKind k : s.nodes.kinds) kinds.push_back(static_cast<std::uint8_t>(k));
  h5::writeDataset(nodes.get(), "kinds", kinds, {n});

  Handle sdf = h5::createGroup(g.get(), "sdf");
  h5::writeAttribute(sdf.get(), "voxel_size", s.sdf.voxelSize);
  h5::writeAttribute(sdf.get(), "background", static_cast<double>(s.sdf.background));
  h5::writeDataset(sdf.get(), "origin", flatten(s.sdf.origin), {3});
  h5::writeDataset(sdf.get(), "values", s.sdf.values,
                   {rows(s.sdf.dims[0]), rows(s.sdf.dims[1]), rows(s.sdf.dims[2])});
}

void writeBodies(hid_t file, const Bundle& bundle) {
  Handle g = h5::createGroup(file, "bodies");
  const hsize_t n = rows(bundle.bodies.size());
  std::vector<std::string> names;
  std::vector<std::int32_t> shape;
  std::vector<double> position, orientation;
  std::vector<std::uint8_t> fixed;
  for (const Body& b : bundle.bodies) {
    names.push_back(b.name);
    shape.push_back(b.shape);
    position.insert(position.end(), {b.position.x(), b.position.y(), b.position.z()});
    const Eigen::Quaterniond q = b.orientation.normalized();
    orientation.insert(orientation.end(), {q.w(), q.x(), q.y(), q.z()});
    fixed.push_back(b.fixed ? 1 : 0);
  }
  h5::writeStrings(g.get(), "names", names);
  h5::writeDataset(g.get(), "shape", shape, {n});
  h5::writeDataset(g.get(), "position", position, {n, 3});
  h5::writeDataset(g.get(), "orientation", orientation, {n, 4});
  h5::writeDataset(g.get(), "fixed", fixed, {n});
  h5::writeAttribute(g.get(), "span_length", bundle.spanLength);
  h5::writeAttribute(g.get(), "span_interfaces", static_cast<std::int64_t>(bundle.spanInterfaces));
  h5::writeAttribute(g.get(), "source_up", bundle.sourceUp);
}

// ---- reading ----

template <class T>
std::vector<T> readRows(hid_t g, const std::string& name, hsize_t columns, const std::string& where) {
  std::vector<hsize_t> dims;
  std::vector<T> data = h5::readDataset<T>(g, name, &dims);
  const bool ok = columns == 0 ? dims.size() == 1 : (dims.size() == 2 && dims[1] == columns);
  if (!ok) throw std::runtime_error(where + "/" + name + " has the wrong shape");
  return data;
}

Shape readShape(hid_t shapes, const std::string& name) {
  Handle g = h5::openGroup(shapes, name);
  const std::string where = "shape '" + name + "'";
  Shape s;
  s.name = name;
  s.source.file = h5::readStringAttribute(g.get(), "source_file");
  s.source.unit = h5::readStringAttribute(g.get(), "source_unit");
  s.source.metresPerUnit = h5::readDoubleAttribute(g.get(), "source_metres_per_unit");
  s.resolution.voxelSize = h5::readDoubleAttribute(g.get(), "voxel_size");
  s.resolution.nodeSpacing = h5::readDoubleAttribute(g.get(), "node_spacing");
  // Bundles written before graded nodes have uniform spacing.
  s.resolution.edgeSpacingFraction = h5::readDoubleAttribute(g.get(), "edge_spacing_fraction", 1.0);
  s.resolution.sizeGradient = h5::readDoubleAttribute(g.get(), "size_gradient", 0.5);
  s.resolution.featureAngle = h5::readDoubleAttribute(g.get(), "feature_angle");
  s.resolution.exteriorBandVoxels = static_cast<int>(h5::readIntAttribute(g.get(), "exterior_band_voxels"));
  s.mass.volume = h5::readDoubleAttribute(g.get(), "volume");
  s.mass.surfaceArea = h5::readDoubleAttribute(g.get(), "surface_area");
  const auto vec3 = [&](const std::string& n) {
    const auto d = readRows<double>(g.get(), n, 0, where);
    if (d.size() != 3) throw std::runtime_error(where + "/" + n + " must hold 3 values");
    return Eigen::Vector3d(d[0], d[1], d[2]);
  };
  const auto mat3 = [&](const std::string& n) { return matrixFrom(readRows<double>(g.get(), n, 3, where)); };
  s.mass.centroid = vec3("centroid");
  s.mass.inertia = mat3("inertia");
  s.mass.principalMoments = vec3("principal_moments");
  s.mass.principalAxes = mat3("principal_axes");

  Handle mesh = h5::openGroup(g.get(), "mesh");
  s.mesh.vertices = unflatten(readRows<double>(mesh.get(), "vertices", 3, where + "/mesh"));
  const auto triangles = readRows<std::int32_t>(mesh.get(), "triangles", 3, where + "/mesh");
  for (std::size_t i = 0; i + 2 < triangles.size(); i += 3) {
    const std::array<int, 3> t{triangles[i], triangles[i + 1], triangles[i + 2]};
    for (int v : t)
      if (v < 0 || v >= static_cast<int>(s.mesh.vertices.size()))
        throw std::runtime_error(where + "/mesh/triangles refers to a vertex that does not exist");
    s.mesh.triangles.push_back(t);
  }

  Handle nodes = h5::openGroup(g.get(), "nodes");
  s.nodes.positions = unflatten(readRows<double>(nodes.get(), "positions", 3, where + "/nodes"));
  s.nodes.normals = unflatten(readRows<double>(nodes.get(), "normals", 3, where + "/nodes"));
  s.nodes.areas = readRows<double>(nodes.get(), "areas", 0, where + "/nodes");
  const auto patches = readRows<std::int32_t>(nodes.get(), "patches", 0, where + "/nodes");
  s.nodes.patches.assign(patches.begin(), patches.end());
  for (std::uint8_t k : readRows<std::uint8_t>(nodes.get(), "kinds", 0, where + "/nodes")) {
    if (k > 2) throw std::runtime_error(where + "/nodes/kinds holds an unknown kind");
    s.nodes.kinds.push_back(static_cast<NodeKind>(k));
  }
  const std::size_t n = s.nodes.positions.size();
  if (s.nodes.normals.size() != n || s.nodes.areas.size() != n || s.nodes.patches.size() != n || s.nodes.kinds.size() != n)
    throw std::runtime_error(where + "/nodes arrays differ in length");

  Handle sdf = h5::openGroup(g.get(), "sdf");
  s.sdf.voxelSize = h5::readDoubleAttribute(sdf.get(), "voxel_size");
  s.sdf.background = static_cast<float>(h5::readDoubleAttribute(sdf.get(), "background"));
  const auto origin = readRows<double>(sdf.get(), "origin", 0, where + "/sdf");
  if (origin.size() != 3) throw std::runtime_error(where + "/sdf/origin must hold 3 values");
  s.sdf.origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  std::vector<hsize_t> dims;
  s.sdf.values = h5::readDataset<float>(sdf.get(), "values", &dims);
  if (dims.size() != 3 || dims[0] < 2 || dims[1] < 2 || dims[2] < 2 || !(s.sdf.voxelSize > 0))
    throw std::runtime_error(where + "/sdf is not a 3-D grid of at least 2 nodes per axis with a positive voxel size");
  for (int a = 0; a < 3; ++a) s.sdf.dims[a] = static_cast<int>(dims[a]);
  s.convex = fitConvexPolyhedron(s.mesh);
  return s;
}

void readBodies(hid_t file, Bundle& bundle) {
  Handle g = h5::openGroup(file, "bodies");
  bundle.spanLength = h5::readDoubleAttribute(g.get(), "span_length");
  bundle.spanInterfaces = static_cast<int>(h5::readIntAttribute(g.get(), "span_interfaces"));
  if (H5Aexists(g.get(), "source_up") > 0) bundle.sourceUp = h5::readStringAttribute(g.get(), "source_up");
  const auto names = h5::readStrings(g.get(), "names");
  const auto shape = readRows<std::int32_t>(g.get(), "shape", 0, "bodies");
  const auto position = readRows<double>(g.get(), "position", 3, "bodies");
  const auto orientation = readRows<double>(g.get(), "orientation", 4, "bodies");
  const auto fixed = readRows<std::uint8_t>(g.get(), "fixed", 0, "bodies");
  const std::size_t n = names.size();
  if (shape.size() != n || position.size() != 3 * n || orientation.size() != 4 * n || fixed.size() != n)
    throw std::runtime_error("bodies arrays differ in length");
  for (std::size_t i = 0; i < n; ++i) {
    Body b;
    b.name = names[i];
    b.shape = shape[i];
    if (b.shape < 0 || b.shape >= static_cast<int>(bundle.shapes.size()))
      throw std::runtime_error("body '" + b.name + "' refers to shape " + std::to_string(b.shape) + ", which does not exist");
    b.position = Eigen::Vector3d(position[3 * i], position[3 * i + 1], position[3 * i + 2]);
    b.orientation = Eigen::Quaterniond(orientation[4 * i], orientation[4 * i + 1], orientation[4 * i + 2], orientation[4 * i + 3]);
    if (std::abs(b.orientation.norm() - 1.0) > 1e-6)
      throw std::runtime_error("body '" + b.name + "' has an orientation that is not a unit quaternion");
    b.fixed = fixed[i] != 0;
    bundle.bodies.push_back(std::move(b));
  }
}

}  // namespace

Bundle readBundle(const std::string& path) {
  const fs::path file = fs::is_directory(path) ? fs::path(path) / kBundleFileName : fs::path(path);
  if (!fs::exists(file))
    throw InputError(file.string() + ": no such bundle; create one with 'tessera prep MESH --unit mm -o DIR'");
  Bundle bundle;
  try {
    Handle f = h5::openFileReadOnly(file.string());
    std::string format;
    try {
      format = h5::readStringAttribute(f.get(), "format");
    } catch (const std::runtime_error&) {
      throw InputError(file.string() + ": not a Tessera bundle (no 'format' attribute)");
    }
    if (format != kBundleFormatName)
      throw InputError(file.string() + ": not a Tessera bundle (format '" + format + "')");
    const auto version = h5::readIntAttribute(f.get(), "format_version");
    if (version != kBundleFormatVersion)
      throw InputError(file.string() + ": bundle format version " + std::to_string(version) + " is not supported (this " +
                       generatorVersion() + " reads version " + std::to_string(kBundleFormatVersion) +
                       "); re-create the bundle with this version");
    bundle.generator = h5::readStringAttribute(f.get(), "generator");
    Handle shapes = h5::openGroup(f.get(), "shapes");
    std::vector<std::pair<std::int64_t, std::string>> order;
    for (const auto& name : h5::childNames(shapes.get())) {
      Handle g = h5::openGroup(shapes.get(), name);
      order.emplace_back(h5::readIntAttribute(g.get(), "index"), name);
    }
    std::sort(order.begin(), order.end());
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (order[i].first != static_cast<std::int64_t>(i)) throw std::runtime_error("shape indices are not 0..n-1");
      bundle.shapes.push_back(readShape(shapes.get(), order[i].second));
    }
    readBodies(f.get(), bundle);
    checkBundleValues(bundle);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(file.string() + ": corrupt or incomplete bundle (" + e.what() + "); re-create it with tessera prep");
  }
  return bundle;
}

void writeBundle(const std::string& directory, const Bundle& bundle) {
  const fs::path dir(directory);
  const bool created = !fs::exists(dir);
  try {
    fs::create_directories(dir);
    // The grids and bundle.h5 replace what was there together, or not at all.
    FileSetWriter files;
    for (const Shape& s : bundle.shapes) writeVdb(files, s.sdf, (dir / (s.name + ".vdb")).string(), s.name);
    h5::addFile(files, dir / kBundleFileName, [&](hid_t f) {
      h5::writeAttribute(f, "format", std::string(kBundleFormatName));
      h5::writeAttribute(f, "format_version", static_cast<std::int64_t>(kBundleFormatVersion));
      h5::writeAttribute(f, "generator", bundle.generator.empty() ? generatorVersion() : bundle.generator);
      h5::writeAttribute(f, "length_unit", std::string("m"));
      Handle shapes = h5::createGroup(f, "shapes");
      for (std::size_t i = 0; i < bundle.shapes.size(); ++i)
        writeShape(shapes.get(), bundle.shapes[i], static_cast<std::int64_t>(i));
      writeBodies(f, bundle);
    });
    files.commit();
  } catch (...) {
    std::error_code ignored;
    if (created) fs::remove_all(dir, ignored);
    throw;
  }
}

}  // namespace tessera

#include "levelset/shape_builder.h"

#include "geometry/input_error.h"
#include "geometry/length_unit.h"
#include "geometry/mesh_features.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_validation.h"
#include "levelset/signed_distance.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace tessera {

namespace {

std::string formatLength(double metres) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4g mm", metres * 1e3);
  return buffer;
}

}  // namespace

bool isValidShapeName(const std::string& name) {
  if (name.empty() || name.size() > 64 || name.front() == '.') return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}

std::string shapeNameFromPath(const std::string& path) {
  std::string name = std::filesystem::path(path).stem().string();
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  while (!name.empty() && name.front() == '.') name.erase(name.begin());
  return name.empty() ? "shape" : name.substr(0, 64);
}

void checkResolution(const Eigen::Vector3d& extents, double surfaceArea, const ShapeResolution& resolution,
                     const std::string& label, PrepLog& log) {
  const double voxel = resolution.voxelSize, spacing = resolution.nodeSpacing;
  if (!(voxel > 0) || !std::isfinite(voxel))
    throw InputError(label + ": voxel size must be positive (got " + std::to_string(voxel) + "); e.g. --voxel 0.25 with --unit mm");
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InputError(label + ": node spacing must be positive (got " + std::to_string(spacing) + "); e.g. --spacing 0.6 with --unit mm");
  if (resolution.exteriorBandVoxels < 1 || resolution.exteriorBandVoxels > 64)
    throw InputError(label + ": exterior band must be 1-64 voxels");

  const double thinnest = extents.minCoeff();
  const double across = thinnest / voxel;
  if (across < 3)
    throw InputError(label + ": voxel size " + formatLength(voxel) + " is too coarse: the thinnest dimension (" +
                     formatLength(thinnest) + ") spans " + std::to_string(across).substr(0, 4) +
                     " voxels, the grid cannot tell inside from outside; use a voxel below " + formatLength(thinnest / 10));
  if (across < 10)
    log.warnings.push_back("under-resolved: the thinnest dimension (" + formatLength(thinnest) + ") spans only " +
                           std::to_string(across).substr(0, 4) + " voxels; use a voxel below " +
                           formatLength(thinnest / 10) + " (rule of thumb: 1/10 of the smallest feature)");
  if (thinnest / spacing < 2)
    log.warnings.push_back("coarse nodes: the thinnest dimension (" + formatLength(thinnest) +
                           ") spans fewer than 2 node spacings; use a spacing below " + formatLength(thinnest / 2));

  const double pad = 2.0 * resolution.exteriorBandVoxels + 3;
  const double gridNodes = (extents.x() / voxel + pad) * (extents.y() / voxel + pad) * (extents.z() / voxel + pad);
  if (gridNodes > 2e8)
    throw InputError(label + ": the grid would have " + std::to_string(static_cast<long long>(gridNodes)) +
                     " nodes (limit 2e8); raise the voxel size or check --unit");
  const double quadrature = 4.0 * surfaceArea / (spacing * spacing) * 144.0;
  if (quadrature > 2e8)
    throw InputError(label + ": node spacing " + formatLength(spacing) + " is too fine for a surface of " +
                     std::to_string(surfaceArea * 1e6) + " mm^2 (about " +
                     std::to_string(static_cast<long long>(surfaceArea / (spacing * spacing))) +
                     " nodes); raise the spacing or check --unit");
  const double largest = extents.maxCoeff();
  if (largest > 10.0 || largest < 1e-4)
    log.warnings.push_back("the shape is " + formatLength(largest) +
                           " across, unusual for a block; check that --unit states the file's unit");
}

Shape buildShape(const std::string& name, TriangleMesh mesh, const ShapeSource& source,
                 const ShapeResolution& resolution, const std::string& label, PrepLog& log) {
  if (!isValidShapeName(name))
    throw InputError(label + ": shape name '" + name + "' is not valid; use 1-64 characters from A-Z a-z 0-9 _ . -");
  if (validateSolidMesh(mesh, label).reoriented)
    log.notes.push_back("the mesh was inside-out (all faces pointing inward); re-oriented it outward");

  Shape shape;
  shape.name = name;
  shape.source = source;
  shape.resolution = resolution;
  shape.mass = computeMassProperties(mesh);
  shape.mesh = toBodyFrame(mesh, shape.mass);
  const Eigen::AlignedBox3d box = boundingBox(shape.mesh.vertices);
  checkResolution(box.sizes(), shape.mass.surfaceArea, resolution, label, log);

  const MeshFeatures features = findFeatures(shape.mesh, resolution.featureAngle);
  SurfaceNodeOptions nodeOptions;
  nodeOptions.spacing = resolution.nodeSpacing;
  nodeOptions.featureAngle = resolution.featureAngle;
  shape.nodes = sampleSurfaceNodes(shape.mesh, features, nodeOptions);

  SignedDistanceOptions sdfOptions;
  sdfOptions.voxelSize = resolution.voxelSize;
  sdfOptions.exteriorBandVoxels = resolution.exteriorBandVoxels;
  shape.sdf = buildSignedDistance(shape.mesh, sdfOptions);
  return shape;
}

Shape prepareShapeFromFile(const std::string& path, const std::string& unitName, const std::string& name,
                           const ShapeResolution& resolution, PrepLog& log) {
  const LengthUnit unit = parseLengthUnit(unitName);
  MeshImportOptions importOptions;
  importOptions.metresPerUnit = unit.metres;
  ImportedMesh imported = importMesh(path, importOptions);
  if (imported.weld.mergedVertices > 0)
    log.notes.push_back("welded " + std::to_string(imported.weld.mergedVertices) + " duplicate vertices (" +
                        std::to_string(imported.fileVertices) + " -> " + std::to_string(imported.mesh.vertices.size()) + ")");
  if (imported.weld.collapsedTriangles > 0)
    log.notes.push_back("dropped " + std::to_string(imported.weld.collapsedTriangles) +
                        " triangles that collapsed when vertices were welded");
  return buildShape(name, std::move(imported.mesh), ShapeSource{path, unit.name, unit.metres}, resolution, path, log);
}

}  // namespace tessera

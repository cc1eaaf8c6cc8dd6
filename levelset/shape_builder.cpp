#include "levelset/shape_builder.h"

#include "io/input_error.h"
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

std::string ShapeEstimate::text() const {
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "grid %lld x %lld x %lld (%.3g M nodes), about %.0f surface nodes, %.3g MB, %.2g s",
                grid[0], grid[1], grid[2], gridNodes * 1e-6, surfaceNodes, bytes * 1e-6, seconds);
  return buffer;
}

ShapeEstimate estimateShape(const Eigen::Vector3d& extents, double surfaceArea, const ShapeResolution& resolution) {
  ShapeEstimate e;
  // As buildSignedDistance lays the grid out: the box in whole voxels, padded by the band.
  e.gridNodes = 1;
  for (int k = 0; k < 3; ++k) {
    e.grid[k] = static_cast<long long>(std::ceil(extents[k] / resolution.voxelSize)) + 2 * resolution.exteriorBandVoxels + 1;
    e.gridNodes *= static_cast<double>(e.grid[k]);
  }
  e.surfaceNodes = surfaceArea / (resolution.nodeSpacing * resolution.nodeSpacing);
  // Graded nodes: along an edge of length L_e, on each of its two faces, the node density 1 / l^2
  // with l = s_e + g d integrates over the band d < (s - s_e) / g to L_e (1/s_e - 1/s) / g, of
  // which L_e (s - s_e) / (g s^2) is counted above. The sharp edges are taken to be those of the
  // bounding box, 4 (a + b + c) (2 334 nodes estimated, 2 584 sampled on the paper's block).
  const double s = resolution.nodeSpacing, edge = resolution.edgeSpacingFraction * s;
  if (edge < s) e.surfaceNodes += 2 * 4 * extents.sum() / resolution.sizeGradient * (s - edge) * (s - edge) / (edge * s * s);
  // Measured with `tessera prep` (/usr/bin/time -v) on the default block at fine voxels and at fine
  // spacings, and on a 180 mm assembly part: 5-25 bytes and 0.4-2 us per grid node (the dense
  // copy, the OpenVDB grid, more for meshes of many triangles); 4.5 kB and 140 us per surface node
  // (the area quadrature). Middle figures are used: an estimate to within a factor of 2-3.
  e.bytes = 16.0 * e.gridNodes + 4500.0 * e.surfaceNodes;
  e.seconds = 1e-6 * e.gridNodes + 140e-6 * e.surfaceNodes;
  return e;
}

void checkResolution(const Eigen::Vector3d& extents, const ShapeResolution& resolution,
                     const std::string& label, PrepLog& log) {
  const double voxel = resolution.voxelSize, spacing = resolution.nodeSpacing;
  if (!(voxel > 0) || !std::isfinite(voxel))
    throw InputError(label + ": voxel size must be positive (got " + std::to_string(voxel) + "); e.g. --voxel 0.25 with --unit mm");
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InputError(label + ": node spacing must be positive (got " + std::to_string(spacing) + "); e.g. --spacing 0.6 with --unit mm");
  if (resolution.exteriorBandVoxels < 1 || resolution.exteriorBandVoxels > 64)
    throw InputError(label + ": exterior band must be 1-64 voxels");

  // OpenVDB's linear transform refuses scales whose cube is below its tolerance (1e-15 m^3).
  if (voxel < 1e-5)
    throw InputError(label + ": voxel size " + formatMillimetres(voxel) + " is below 0.01 mm, the finest the OpenVDB grid "
                     "(in metres) holds; coarsen --voxel, or check --unit");
  const double thinnest = extents.minCoeff();
  const double across = thinnest / voxel;
  if (across < 3)
    throw InputError(label + ": voxel size " + formatMillimetres(voxel) + " is too coarse: the thinnest dimension (" +
                     formatMillimetres(thinnest) + ") spans " + std::to_string(across).substr(0, 4) +
                     " voxels, the grid cannot tell inside from outside; use a voxel below " + formatMillimetres(thinnest / 10));
  if (across < 10)
    log.warnings.push_back("under-resolved: the thinnest dimension (" + formatMillimetres(thinnest) + ") spans only " +
                           std::to_string(across).substr(0, 4) + " voxels; use a voxel below " +
                           formatMillimetres(thinnest / 10) + " (rule of thumb: 1/10 of the smallest feature)");
  const double largest = extents.maxCoeff();
  if (spacing > largest)  // 1e300 m gave "-nan surface nodes"
    throw InputError(label + ": node spacing " + formatMillimetres(spacing) + " is larger than the block (" +
                     formatMillimetres(largest) + " across), so no node falls on a face; use a spacing below " +
                     formatMillimetres(thinnest / 2) + ", or check --unit");
  if (thinnest / spacing < 2)
    log.warnings.push_back("coarse nodes: the thinnest dimension (" + formatMillimetres(thinnest) +
                           ") spans fewer than 2 node spacings; use a spacing below " + formatMillimetres(thinnest / 2));

}

Shape buildShape(const std::string& name, TriangleMesh mesh, const ShapeSource& source,
                 const ShapeResolution& resolution, const std::string& label, PrepLog& log,
                 const ShapeLimits& limits) {
  if (!isValidShapeName(name))
    throw InputError(label + ": shape name '" + name + "' is not valid; use 1-64 characters from A-Z a-z 0-9 _ . -");
  if (validateSolidMesh(mesh, label).reoriented)
    log.notes.push_back("the mesh was inside-out (all faces pointing inward); re-oriented it outward");

  Shape shape;
  shape.name = name;
  shape.source = source;
  shape.mass = computeMassProperties(mesh);
  shape.mesh = toBodyFrame(mesh, shape.mass);
  const Eigen::Vector3d extents = boundingBox(shape.mesh.vertices).sizes();
  const double largest = extents.maxCoeff();
  if (!limits.anySize && (largest < limits.smallest || largest > limits.largest))
    throw InputError(label + ": the block is " + formatMillimetres(largest) + " across read as " + source.unit +
                     ", outside " + formatMillimetres(limits.smallest) + " to " + formatMillimetres(limits.largest) +
                     ": check --unit (mesh files carry no unit), or pass --any-size if that size is meant");
  const ShapeResolution resolved = resolution.resolvedFor(extents.minCoeff());
  shape.resolution = resolved;
  checkResolution(extents, resolved, label, log);
  const ShapeEstimate estimate = estimateShape(extents, shape.mass.surfaceArea, resolved);
  if (estimate.bytes > limits.maxMemoryBytes) {
    char budget[160];
    std::snprintf(budget, sizeof budget, "needs about %.3g GB, above the budget of %.3g GB", estimate.bytes * 1e-9,
                  limits.maxMemoryBytes * 1e-9);
    throw InputError(label + ": voxel " + formatMillimetres(resolved.voxelSize) + " and spacing " +
                     formatMillimetres(resolved.nodeSpacing) + " on a block " + formatMillimetres(largest) + " across " + budget +
                     " (" + estimate.text() + "); coarsen --voxel/--spacing (default: relative to the block), "
                     "check --unit, or raise --max-memory");
  }
  if (log.now)
    log.now("voxel " + formatMillimetres(resolved.voxelSize) + ", spacing " + formatMillimetres(resolved.nodeSpacing) +
            "; estimate: " + estimate.text());

  const MeshFeatures features = findFeatures(shape.mesh, resolution.featureAngle);
  SurfaceNodeOptions nodeOptions;
  nodeOptions.spacing = resolved.nodeSpacing;
  nodeOptions.edgeSpacing = resolved.edgeSpacingFraction * resolved.nodeSpacing;
  nodeOptions.sizeGradient = resolved.sizeGradient;
  nodeOptions.featureAngle = resolved.featureAngle;
  shape.nodes = sampleSurfaceNodes(shape.mesh, features, nodeOptions);

  SignedDistanceOptions sdfOptions;
  sdfOptions.voxelSize = resolved.voxelSize;
  sdfOptions.exteriorBandVoxels = resolved.exteriorBandVoxels;
  shape.sdf = buildSignedDistance(shape.mesh, sdfOptions);
  shape.convex = fitConvexPolyhedron(shape.mesh);
  return shape;
}

Shape prepareShapeFromFile(const std::string& path, const std::string& unitName, const std::string& name,
                           const ShapeResolution& resolution, PrepLog& log, const ShapeLimits& limits,
                           const std::string& up) {
  const LengthUnit unit = parseLengthUnit(unitName);
  MeshImportOptions importOptions;
  importOptions.metresPerUnit = unit.metres;
  importOptions.up = up;
  ImportedMesh imported = importMesh(path, importOptions);
  if (imported.weld.mergedVertices > 0)
    log.notes.push_back("welded " + std::to_string(imported.weld.mergedVertices) + " duplicate vertices (" +
                        std::to_string(imported.fileVertices) + " -> " + std::to_string(imported.mesh.vertices.size()) + ")");
  if (imported.weld.collapsedTriangles > 0)
    log.notes.push_back("dropped " + std::to_string(imported.weld.collapsedTriangles) +
                        " triangles that collapsed when vertices were welded");
  return buildShape(name, std::move(imported.mesh), ShapeSource{path, unit.name, unit.metres}, resolution, path, log,
                    limits);
}

}  // namespace tessera

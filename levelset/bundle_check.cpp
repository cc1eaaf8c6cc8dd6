#include "levelset/bundle_check.h"

#include "geometry/mass_properties.h"
#include "geometry/mesh_validation.h"
#include "geometry/point_mesh_distance.h"
#include "io/input_error.h"

#include <cmath>
#include <set>
#include <stdexcept>

namespace tessera {

namespace {

constexpr double kUnitTolerance = 1e-6;  // |n| and |q| of a unit vector stored in double (or float) precision

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

bool positiveFinite(double x) { return std::isfinite(x) && x > 0; }

bool near(double a, double b, double tolerance) { return std::abs(a - b) <= tolerance; }

void checkResolution(const ShapeResolution& r, const std::string& name) {
  require(positiveFinite(r.voxelSize) && positiveFinite(r.nodeSpacing), name + "a voxel size or node spacing that is not finite and positive");
  require(validEdgeSpacingFraction(r.edgeSpacingFraction) && validSizeGradient(r.sizeGradient) && r.featureAngle > 0 &&
              r.featureAngle < M_PI && r.exteriorBandVoxels >= 1 && r.exteriorBandVoxels <= 1000,
          name + "a node grading, feature angle or band out of range");
}

// What the shape records about its mesh, recomputed from the mesh (the mesh is the shape; the
// rest is derived from it by prep, so anything else is damage): a closed, outward, not
// self-intersecting surface; its volume, centroid (the body frame's origin), principal moments
// and surface area; nodes on it whose areas sum to its area; principal axes that are a rotation.
void checkAgainstMesh(const Shape& s, const std::string& name) {
  TriangleMesh mesh = s.mesh;
  try {
    require(!validateSolidMesh(mesh, "mesh").reoriented, name + "its mesh faces inward");
  } catch (const InputError& e) {
    throw std::invalid_argument(name + e.what());
  }
  const MassProperties m = computeMassProperties(mesh);
  const double size = boundingBox(mesh.vertices).diagonal().norm(), relative = 1e-6;
  require(near(m.volume, s.mass.volume, relative * m.volume) && near(m.surfaceArea, s.mass.surfaceArea, relative * m.surfaceArea),
          name + "a volume or surface area that is not its mesh's");
  require(m.centroid.norm() <= relative * size, name + "its mesh is not centred on its centroid (the body frame's origin)");
  const double moment = m.principalMoments.maxCoeff();
  for (int k = 0; k < 3; ++k)
    require(near(m.inertia(k, k), s.mass.principalMoments[k], relative * moment), name + "principal moments that are not its mesh's");
  const Eigen::Matrix3d& axes = s.mass.principalAxes;
  require(s.mass.centroid.allFinite() && s.mass.inertia.allFinite() && axes.allFinite() &&
              (axes.transpose() * axes - Eigen::Matrix3d::Identity()).norm() <= 1e-9 && axes.determinant() > 0,
          name + "a centroid, inertia or principal axes that are not finite, or axes that are not a rotation");
  double area = 0;
  for (double a : s.nodes.areas) area += a;
  require(near(area, m.surfaceArea, relative * m.surfaceArea), name + "node areas that do not sum to the mesh's surface area");
  const PointMeshDistance surface(mesh);
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    require(surface.distance(s.nodes.positions[i]) <= 1e-4 * size, name + "node " + std::to_string(i) + " is off the mesh's surface");
}

void checkShape(const Shape& s) {
  const std::string name = "shape '" + s.name + "': ";
  require(!s.name.empty(), "a shape without a name");
  const std::size_t vertices = s.mesh.vertices.size();
  require(vertices >= 4 && s.mesh.triangles.size() >= 4, name + "a mesh of fewer than 4 vertices or triangles");
  for (const auto& v : s.mesh.vertices) require(v.allFinite(), name + "a mesh vertex is not finite");
  for (const auto& t : s.mesh.triangles)
    for (int k : t) require(k >= 0 && static_cast<std::size_t>(k) < vertices, name + "a triangle names no vertex");
  const SurfaceNodes& n = s.nodes;
  require(n.size() >= 4, name + "fewer than 4 surface nodes");
  require(n.normals.size() == n.size() && n.areas.size() == n.size(), name + "node arrays of different lengths");
  for (std::size_t i = 0; i < n.size(); ++i) {
    require(n.positions[i].allFinite(), name + "node " + std::to_string(i) + " has a non-finite position");
    require(n.normals[i].allFinite() && std::abs(n.normals[i].norm() - 1) < kUnitTolerance,
            name + "node " + std::to_string(i) + " has a normal that is not a unit vector");
    require(positiveFinite(n.areas[i]), name + "node " + std::to_string(i) + " has a zero, negative or non-finite area");
  }
  const DenseSdf& g = s.sdf;
  require(g.origin.allFinite() && positiveFinite(g.voxelSize), name + "the grid's origin or voxel size is not finite and positive");
  require(g.dims[0] >= 2 && g.dims[1] >= 2 && g.dims[2] >= 2, name + "a grid of fewer than 2 nodes along an axis");
  require(g.values.size() == static_cast<std::size_t>(g.dims[0]) * g.dims[1] * g.dims[2], name + "grid values do not match its size");
  for (float v : g.values) require(std::isfinite(v), name + "a grid value is not finite");
  require(positiveFinite(s.mass.volume) && s.mass.principalMoments.allFinite() && (s.mass.principalMoments.array() > 0).all(),
          name + "a volume or principal moment that is not finite and positive");
  checkResolution(s.resolution, name);
  require(std::abs(g.voxelSize - s.resolution.voxelSize) <= 1e-9 * s.resolution.voxelSize,
          name + "the grid's voxel is not the recorded voxel size");
  checkAgainstMesh(s, name);
  if (s.convex)
    for (const FacePlane& p : s.convex->planes)
      require(p.normal.allFinite() && std::isfinite(p.offset) && std::abs(p.normal.norm() - 1) < kUnitTolerance,
              name + "a face plane that is not finite with a unit normal");
}

}  // namespace

void checkBundleValues(const Bundle& bundle) {
  for (const Shape& s : bundle.shapes) checkShape(s);
  std::set<std::string> names;
  for (const Body& b : bundle.bodies) {
    require(!b.name.empty(), "a body without a name");
    const std::string name = "body '" + b.name + "': ";
    require(names.insert(b.name).second, name + "a second body of that name");
    require(b.shape >= 0 && static_cast<std::size_t>(b.shape) < bundle.shapes.size(), name + "names no shape");
    require(b.position.allFinite(), name + "its position is not finite");
    require(b.orientation.coeffs().allFinite() && std::abs(b.orientation.norm() - 1) < kUnitTolerance,
            name + "its orientation is not a unit quaternion");
  }
  require(std::isfinite(bundle.spanLength) && bundle.spanLength >= 0 && bundle.spanInterfaces >= 0,
          "the span (length, interfaces) is negative or not finite");
}

}  // namespace tessera

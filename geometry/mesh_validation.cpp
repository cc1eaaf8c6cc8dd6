#include "geometry/mesh_validation.h"

#include "io/input_error.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_topology.h"
#include "geometry/self_intersection.h"

#include <cmath>
#include <cstdio>
#include <utility>

namespace tessera {

namespace {

std::string at(const Eigen::Vector3d& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g) m", p.x(), p.y(), p.z());
  return buffer;
}

std::string edgeAt(const TriangleMesh& mesh, const MeshEdge& e) {
  return "edge " + at(mesh.vertices[e.vertices[0]]) + " - " + at(mesh.vertices[e.vertices[1]]);
}

[[noreturn]] void refuse(const std::string& label, const std::string& problem, const std::string& fix) {
  throw InputError(label + ": " + problem + "; " + fix);
}

}  // namespace

ValidationReport validateSolidMesh(TriangleMesh& mesh, const std::string& label) {
  const std::size_t triangleCount = mesh.triangles.size();
  if (triangleCount < 4)
    refuse(label, "only " + std::to_string(triangleCount) + " triangle(s); a closed solid needs at least 4",
           "give the closed surface of a solid");

  const double diagonal = boundingBox(mesh.vertices).diagonal().norm();
  for (int t = 0; t < static_cast<int>(triangleCount); ++t)
    if (triangleArea(mesh, t) <= 1e-14 * diagonal * diagonal)
      refuse(label, "triangle " + std::to_string(t) + " at " + at(triangleCorner(mesh, t, 0)) + " has zero area",
             "remove degenerate triangles in a mesh tool (e.g. MeshLab: Remove Zero Area Faces)");

  const MeshTopology topology = buildTopology(mesh);
  std::size_t open = 0, nonManifold = 0, flipped = 0;
  const MeshEdge* firstOpen = nullptr;
  const MeshEdge* firstNonManifold = nullptr;
  const MeshEdge* firstFlipped = nullptr;
  for (const MeshEdge& e : topology.edges) {
    if (e.triangles.size() == 1) {
      if (open++ == 0) firstOpen = &e;
    } else if (e.triangles.size() > 2) {
      if (nonManifold++ == 0) firstNonManifold = &e;
    } else if (e.forwardUses != 1) {
      if (flipped++ == 0) firstFlipped = &e;
    }
  }
  if (open > 0)
    refuse(label, "the mesh is open (not watertight): " + std::to_string(open) + " boundary edge(s), e.g. " +
                      edgeAt(mesh, *firstOpen),
           "close the holes (e.g. MeshLab: Close Holes) or export the solid as a closed mesh");
  if (nonManifold > 0)
    refuse(label, "non-manifold: " + std::to_string(nonManifold) + " edge(s) shared by more than two triangles, e.g. " +
                      edgeAt(mesh, *firstNonManifold) + " (" +
                      std::to_string(firstNonManifold->triangles.size()) + " triangles)",
           "split the touching parts or remove the extra faces so each edge joins exactly two triangles");
  if (flipped > 0)
    refuse(label, "inconsistent orientation: " + std::to_string(flipped) +
                      " edge(s) where neighbouring triangles face opposite ways, e.g. " + edgeAt(mesh, *firstFlipped),
           "unify the face orientation in a mesh tool (e.g. MeshLab: Re-Orient all faces coherently)");

  const std::vector<int> pinched = nonManifoldVertices(mesh, topology);
  if (!pinched.empty())
    refuse(label, "non-manifold: " + std::to_string(pinched.size()) + " vertex(es) where separate sheets touch, e.g. " +
                      at(mesh.vertices[pinched.front()]),
           "separate the sheets so that the surface around each vertex is a single fan");

  std::vector<int> component;
  const int components = connectedComponents(mesh, topology, component);
  if (components > 1)
    refuse(label, "the mesh has " + std::to_string(components) + " separate pieces; a shape is one solid",
           "split the file into one mesh per block");

  const double volume = signedVolume(mesh);
  if (std::abs(volume) <= 1e-9 * diagonal * diagonal * diagonal)
    refuse(label, "the mesh encloses no volume (degenerate: flat or folded onto itself)",
           "give the closed surface of a solid with thickness");

  const auto intersections = findSelfIntersections(mesh);
  if (!intersections.empty()) {
    const auto [a, b] = intersections.front();
    refuse(label, "self-intersecting: " + std::to_string(intersections.size()) + " pair(s) of triangles cross, e.g. " +
                      std::to_string(a) + " at " + at(triangleCorner(mesh, a, 0)) + " and " + std::to_string(b) +
                      " at " + at(triangleCorner(mesh, b, 0)),
           "remove the intersections in a mesh tool (e.g. a boolean union, or MeshLab: Select Self Intersecting Faces)");
  }

  ValidationReport report;
  if (volume < 0) {
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    report.reoriented = true;
  }
  return report;
}

}  // namespace tessera

// The one translation unit of geometry/ that includes CGAL (its headers are heavy to compile).
#include "geometry/self_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>
#include <stdexcept>

namespace tessera {

std::vector<std::pair<int, int>> findSelfIntersections(const TriangleMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
  Surface surface;
  std::vector<Surface::Vertex_index> vertex;
  vertex.reserve(mesh.vertices.size());
  for (const auto& p : mesh.vertices) vertex.push_back(surface.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (const auto& t : mesh.triangles)
    if (surface.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == Surface::null_face())
      throw std::logic_error("findSelfIntersections: mesh is not a manifold (validate its topology first)");

  // Surface_mesh numbers faces in insertion order, so face index == triangle index.
  std::vector<std::pair<Surface::Face_index, Surface::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(surface, std::back_inserter(pairs));
  std::vector<std::pair<int, int>> out;
  out.reserve(pairs.size());
  for (const auto& [a, b] : pairs) out.emplace_back(static_cast<int>(a.idx()), static_cast<int>(b.idx()));
  return out;
}

}  // namespace tessera

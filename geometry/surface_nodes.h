#pragma once
#include "geometry/mesh_features.h"
#include "geometry/mesh_symmetry.h"
#include "geometry/triangle_mesh.h"

#include <cstdint>
#include <vector>

namespace tessera {

enum class NodeKind : std::uint8_t { Face = 0, Edge = 1, Corner = 2 };

/// Node spacing, uniform or graded towards the sharp edges: the local spacing is
/// l(x) = min(spacing, edgeSpacing + sizeGradient d(x)), d the distance from x to the nearest sharp
/// edge bounding its patch. Blocks hinge on their edges, so the traction there varies fastest.
struct SurfaceNodeOptions {
  double spacing = 0.6e-3;         ///< m; target distance between neighbouring nodes on face interiors
  double edgeSpacing = 0.0;        ///< m; spacing along sharp edges and at corners (0, or >= spacing: uniform)
  double sizeGradient = 0.5;       ///< growth of the spacing per unit distance from a sharp edge
  double featureAngle = 0.5236;    ///< rad (30 deg); edges bending more than this are sharp
  int quadraturePerSpacing = 12;   ///< area quadrature points per spacing length (area accuracy)
  bool keepSymmetries = true;      ///< nodes with the block's mirror and rotational symmetries (findSymmetries)
};

/// Surface nodes of a solid with area weights, as arrays (one entry per node).
/// Every node is the quadrature point of one cell of one patch (a face region between sharp
/// edges): it carries the cell's area, the cell's mean outward normal and sits on the surface at
/// the cell's centroid.
/// Cells are seeded on every corner and along every sharp edge, once per patch meeting there, so
/// each patch's weights sum to the patch area, every node's normal is a face normal (never an
/// average across an edge), and edges are lined with nodes a quarter spacing inside each face.
struct SurfaceNodes {
  std::vector<Eigen::Vector3d> positions;  ///< m
  std::vector<Eigen::Vector3d> normals;    ///< unit, outward
  std::vector<double> areas;               ///< m^2; sum = surface area
  std::vector<int> patches;                ///< patch id (see MeshFeatures)
  std::vector<NodeKind> kinds;
  std::size_t symmetries = 1;              ///< order of the block's symmetry group the nodes keep (1: none)

  std::size_t size() const { return positions.size(); }
};

/// Samples nodes on a validated, outward-oriented mesh:
///  - a node at every corner;
///  - nodes along every sharp-edge chain, evenly at most the edge spacing apart;
///  - face nodes by farthest-point sampling of each patch over candidate points (centroids of
///    sub-triangles of edge <= l / 4), seeded with the patch's edge and corner nodes and
///    stopped when every candidate is within 0.9 l of a node (this leaves neighbouring nodes
///    about l apart), distances measured in units of the local spacing l;
///  - cells: each triangle is cut into small quadrature triangles (edge <= l /
///    quadraturePerSpacing), each given wholly to the nearest seed of the same patch (a discrete
///    Voronoi partition); a node's area is its cell's area (the weights sum to the area exactly up
///    to rounding) and its position the cell's centroid moved onto the cell's surface (the
///    closest point of the cell's triangles; on a planar cell, the centroid itself). Centroids
///    make each node a midpoint rule for its cell (exact for tractions linear over the cell), and
///    keep nodes off the edges, where the distance to a body whose face ends at the same edge
///    would read zero; the move onto the surface keeps a node on a curved face from sitting off it
///    by the sagitta of its cell (about kappa l^2 / 8), which a matching neighbour would read as
///    overlap.
///  - symmetries (keepSymmetries): a block with mirror or rotational symmetries (findSymmetries)
///    gets a node set with the same symmetries, to rounding: each orbit of patches is sampled on
///    one patch, within the fundamental region of the maps that keep that patch, and mapped to the
///    others; each node's area, normal and position are then the mean over its orbit.
/// Throws InputError when spacing <= 0 or sizeGradient <= 0.
SurfaceNodes sampleSurfaceNodes(const TriangleMesh& mesh, const MeshFeatures& features,
                                const SurfaceNodeOptions& options);

/// How many elements of `group` the node set keeps: those that map every node onto a node of the
/// same area (relative 1e-9), within `tolerance` (m). A bundle's nodes sampled before nodes kept
/// symmetries keep the identity alone.
std::size_t keptSymmetries(const SurfaceNodes& nodes, const SymmetryGroup& group, double tolerance);

}  // namespace tessera

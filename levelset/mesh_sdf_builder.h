#pragma once
#include "geometry/triangle_mesh.h"
#include "levelset/dense_sdf.h"
#include "levelset/mesh_sdf.h"

namespace tessera {

/// The exact level set of a closed, outward-oriented mesh on the cells of `grid` (its voxels;
/// the grid's values, exact distances at its nodes, tell which cells are near the surface). Every cell within `band` (m) of the surface lists the triangles that can
/// hold the closest point of any point in it: with c the cell's centre, d_c its distance to the
/// mesh and D the cell's diagonal, a triangle farther than d_c + D from c is farther from every
/// point p of the cell than p's closest triangle (|p - c| <= D / 2, both ways). Edges not shared
/// by exactly two triangles take their own face's normal as pseudo-normal.
MeshSdf buildMeshSdf(const TriangleMesh& mesh, const DenseSdf& grid, double band);

}  // namespace tessera

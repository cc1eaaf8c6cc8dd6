#pragma once
#include "geometry/mesh_topology.h"
#include "geometry/triangle_mesh.h"

#include <vector>

namespace tessera {

/// A run of sharp edges between two corners (or a closed loop of them).
struct FeatureChain {
  std::vector<int> vertices;  ///< polyline; for a closed loop the first vertex is repeated at the end
  bool closed = false;
  std::vector<int> patches;   ///< the one or two patches that meet along the chain
};

/// Sharp features of a closed manifold mesh. An edge is sharp when the normals of its two
/// triangles differ by more than the feature angle; patches are the regions between sharp
/// edges (a flat face of a block, or all of a smooth sphere); corners are vertices where the
/// sharp edges do not continue as one smooth line.
struct MeshFeatures {
  MeshTopology topology;
  std::vector<char> edgeIsSharp;   ///< per topology edge
  std::vector<int> trianglePatch;  ///< patch id per triangle
  int patchCount = 0;
  std::vector<int> corners;        ///< vertex ids: sharp degree 1 or >= 3, or a turn above the feature angle
  std::vector<FeatureChain> chains;
};

/// Precondition: `mesh` passed validateSolidMesh. `featureAngle` in radians.
MeshFeatures findFeatures(const TriangleMesh& mesh, double featureAngle);

}  // namespace tessera

#pragma once
#include "geometry/plane_tiling.h"

#include <vector>

namespace tessera {

/// Signs for a plane slab that interlocks where the sign rule's do not (interlockingTilts: a tiling
/// of odd cells, such as Voronoi's, cannot alternate, and some groups of its blocks then have a
/// way out). A greedy search over the interlocking program (largestOpening, docs/check.md): each
/// shared edge with a free tile on either side is flipped in turn and the flip kept when both its
/// tiles stay held by their neighbours (heldByNeighbours) and the program's optimum drops; sweeps
/// until it is 0, or no flip lowers it, or kSweeps have run. The program is posed on the slab's
/// model: over each shared edge, the quadrilateral of its tilted face between z = -h/2 and h/2
/// (corner cuts and the trimming by neighbouring faces left out; `tessera check` judges the blocks
/// themselves), bodies turning about their tiles' centroids. `fixed`: per tile.
/// Returns whether the model is interlocked with the tilts it leaves: they are changed only when it
/// is (a slab the search cannot interlock, such as a triangle slab, keeps the rule's signs), and
/// not at all beyond kMaxTiles tiles (each program grows with the slab, and so does their number:
/// 9 x 9 Voronoi tiles took 50-390 programs, 2-14 s on 2 cores).
struct InterlockingSearch {
  static constexpr int kSweeps = 8;
  static constexpr int kMaxTiles = 150;
  int flips = 0;      ///< flips kept
  int programs = 0;   ///< interlocking programs solved
  bool interlocked = false;
  bool tooLarge = false;  ///< more than kMaxTiles tiles: not searched
};
InterlockingSearch interlockSigns(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across,
                                  const std::vector<char>& fixed, double thickness, double angle,
                                  std::vector<std::vector<int>>& tilts);

}  // namespace tessera

#pragma once
#include "geometry/base_surface.h"
#include "geometry/plane_tiling.h"

#include <vector>

namespace tessera {

/// Signs for a slab (on the plane or a base surface) that interlocks where the sign rule's do not
/// (interlockingTilts: a tiling of odd cells, such as Voronoi's, cannot alternate, and groups of
/// its blocks then have a way out). A greedy search over the interlocking program (largestOpening,
/// docs/check.md): each shared edge with a free tile on either side is flipped in turn and the
/// flip kept when both its tiles stay held by their neighbours (heldByNeighbours) and the
/// program's optimum drops; sweeps go over the edges next to a tile the last way out moves, then
/// over every edge, until the optimum is 0, or no flip lowers it, or kSweeps have run. The
/// program is posed on the blocks the signs make (tiltedBlock, corner cuts included): over each
/// shared edge the two blocks' common face, shrunk for a margin (docs/tiling.md); bodies turning
/// about their middles. `fixed`: per tile; with none fixed nothing can interlock, and the tilts
/// are left as they are (programs = 0).
/// The tilts are changed only when the search ends interlocked (a slab it cannot interlock, such
/// as a triangle slab, keeps the rule's signs), and not at all beyond kMaxTiles tiles (each program
/// grows with the slab, and so does their number: 9 x 9 Voronoi tiles took 50-271 programs, 2-9 s
/// on 2 cores).
struct InterlockingSearch {
  static constexpr int kSweeps = 8;
  static constexpr int kMaxTiles = 150;
  int flips = 0;      ///< flips kept
  int programs = 0;   ///< interlocking programs solved
  bool interlocked = false;
  bool tooLarge = false;  ///< more than kMaxTiles tiles: not searched
};
InterlockingSearch interlockSigns(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across,
                                  const std::vector<char>& fixed, double thickness, double angle, const BaseSurface& surface,
                                  std::vector<std::vector<int>>& tilts);

}  // namespace tessera

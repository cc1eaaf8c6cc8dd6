#include "levelset/shape.h"

#include <cstdio>

namespace tessera {

std::string levelSetPath(const Shape& shape, bool exactConvexLevelSets) {
  if (!shape.convex) return "grid (not convex)";
  if (!exactConvexLevelSets) return "grid (exact planes off)";
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "exact planes (%zu faces, convex to %.2g mm)", shape.convex->planes.size(),
                shape.convex->deviation * 1e3);
  return buffer;
}

}  // namespace tessera

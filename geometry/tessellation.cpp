#include "geometry/tessellation.h"

#include "io/input_error.h"

#include <algorithm>
#include <cmath>

namespace tessera {

std::vector<Placement> squareGrid(const SquareGridOptions& o, const std::string& shape) {
  if (o.columns < 1 || o.rows < 1) throw InputError("--grid: need at least 1 x 1 blocks");
  if (!(o.pitch > 0) || !std::isfinite(o.pitch)) throw InputError("--pitch must be positive");
  if (!(o.gap >= 0) || !std::isfinite(o.gap)) throw InputError("--gap must be zero or positive");
  if (o.fixPerimeter && std::min(o.columns, o.rows) < 3)
    throw InputError("--grid " + std::to_string(o.columns) + "x" + std::to_string(o.rows) +
                     " with --fix perimeter: every block is on the perimeter, so none is free to load; use at least 3x3, "
                     "or --fix none");
  const double p = o.pitch + o.gap;
  const Eigen::Quaterniond quarterTurn(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  std::vector<Placement> out;
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.columns; ++c) {
      Placement b;
      b.name = "r" + std::to_string(r) + "c" + std::to_string(c);
      b.shape = shape;
      b.translation = Eigen::Vector3d((c - 0.5 * (o.columns - 1)) * p, (r - 0.5 * (o.rows - 1)) * p, 0.0);
      if (o.alternate && (r + c) % 2 == 1) b.rotation = quarterTurn;
      b.fixed = o.fixPerimeter && (r == 0 || c == 0 || r == o.rows - 1 || c == o.columns - 1);
      out.push_back(b);
    }
  return out;
}

InterlockingSpan squareGridSpan(const SquareGridOptions& o) {
  const int n = std::min(o.columns, o.rows);
  if (!o.fixPerimeter || n < 3) return {};
  return {(n - 2) * (o.pitch + o.gap), n - 1};
}

}  // namespace tessera

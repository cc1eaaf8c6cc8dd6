#pragma once
#include "levelset/bundle.h"
#include "solver/scene.h"
#include "solver/world.h"

namespace tessera {

/// Where the indenter comes down: the body it loads and the point in plan (x, y). indenter.point:
/// the body whose surface is highest on the vertical through it; else indenter.target (default:
/// centralFreeBody) at its centroid plus indenter.offset. Throws std::invalid_argument for an
/// unknown target, a point on no body or on a fixed one, or an offset off the target.
struct LoadPoint {
  int body = -1;
  Eigen::Vector2d at{0, 0};  ///< m
};
LoadPoint chooseLoadPoint(const World& world, const Bundle& bundle, const IndenterSettings& indenter);

}  // namespace tessera

#pragma once
#include "levelset/bundle.h"
#include "run/scene.h"

#include <optional>
#include <utility>

namespace tessera {

/// m, the bottom and top (along z, the loading direction) of a mesh posed at (orientation,
/// position): a body's thickness h is their difference.
std::pair<double, double> heightRange(const TriangleMesh& mesh, const Eigen::Quaterniond& orientation,
                                      const Eigen::Vector3d& position);

/// m, the lowest and highest points of a mesh posed at (orientation, position) on the vertical
/// line through `at` (x, y); nothing when the line misses it.
std::optional<std::pair<double, double>> verticalExtent(const TriangleMesh& mesh, const Eigen::Quaterniond& orientation,
                                                        const Eigen::Vector3d& position, const Eigen::Vector2d& at);

/// m, the loaded block's thickness h along the loading direction: its extent on the vertical
/// through the load point `at` (a tilted block's is about t / cos(tilt), not its z-extent: a dome
/// block 100 mm thick, tilted, spans 177 mm in z), or its z-extent where that line misses it. h sets
/// K's fit window, the indenter's radius and delta_max (their ratios).
double loadedThickness(const TriangleMesh& mesh, const Eigen::Quaterniond& orientation, const Eigen::Vector3d& position,
                       const Eigen::Vector2d& at);

/// m, the height of the centre of a sphere of `radius` coming down the vertical through `at` (x, y)
/// when it first touches a body posed at (orientation, position): the highest z_i + sqrt(R^2 - r_i^2)
/// over the body's surface nodes within R of that vertical (r_i the distance from it). The solver
/// finds contact at exactly these nodes (each against the sphere's level set), so a sphere put this
/// high touches nothing. Nothing when no node is within R.
std::optional<double> sphereTouchHeight(const SurfaceNodes& nodes, const Eigen::Quaterniond& orientation,
                                        const Eigen::Vector3d& position, const Eigen::Vector2d& at, double radius);

/// Where the indenter comes down, decided once from the bundle's poses, before any work (so a
/// resumed run loads the same body): the body it loads and the plan offset (x, y) from that body's
/// centroid. indenter.point: the body whose surface is highest on the vertical through it; else
/// indenter.target (default: centralFreeBody) with indenter.offset. After settling, the indenter
/// comes down at the body's settled centroid plus the offset. Throws std::invalid_argument for an
/// unknown or fixed target, a point on no body or on a fixed one, or an offset off the target.
struct LoadPoint {
  int body = -1;
  Eigen::Vector2d offset{0, 0};  ///< m, in plan from the body's centroid
};
LoadPoint chooseLoadPoint(const Bundle& bundle, const IndenterSettings& indenter);

/// The free body nearest the bodies' mean centroid in plan (x, y): the default target.
int centralFreeBody(const Bundle& bundle);

}  // namespace tessera

#include "levelset/contact_polygons.h"

#include "geometry/plane_tiling.h"

#include <algorithm>
#include <cmath>

namespace tessera {

namespace {

const double kSameNormal = std::cos(10 * M_PI / 180);  // normals within 10 degrees
constexpr std::size_t kMostCorners = 8;                // per contact polygon

// Drops the corner that spans the smallest triangle with its neighbours (Visvalingam & Whyatt,
// Cartographic J. 30, 1993) while more than `most` remain or that triangle is below 0.5 % of the
// polygon's area (a corner of the hull that only rounds a straight side): a convex polygon only
// shrinks, so the contact is not made larger than it is.
std::vector<Eigen::Vector2d> simplified(std::vector<Eigen::Vector2d> polygon, std::size_t most) {
  const double area = polygonArea(polygon);
  while (polygon.size() > 3) {
    std::size_t smallest = 0;
    double least = 1e300;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d& p = polygon[(i + polygon.size() - 1) % polygon.size()];
      const Eigen::Vector2d& n = polygon[(i + 1) % polygon.size()];
      const Eigen::Vector2d a = polygon[i] - p, b = n - p;
      const double triangle = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
      if (triangle < least) least = triangle, smallest = i;
    }
    if (polygon.size() <= most && least >= 0.005 * area) break;
    polygon.erase(polygon.begin() + static_cast<long>(smallest));
  }
  return polygon;
}

struct TouchingNode {
  Eigen::Vector3d point, normal;  // world; normal from the pair's first body into its second
};

// Calls visit(i, point, own, outward) for every surface node i of body `from` within `touch` of
// body `to`'s surface: its world point, its own outward normal and `to`'s outward normal there.
template <class Visit>
void forTouchingNodes(const Bundle& bundle, const AssemblyLevelSets& levelSets, int from, int to, double touch, Visit&& visit) {
  const Body& a = bundle.bodies[from];
  const Body& b = bundle.bodies[to];
  const Eigen::Matrix3d ra = a.orientation.toRotationMatrix(), rb = b.orientation.toRotationMatrix();
  const SurfaceNodes& nodes = bundle.shapes[a.shape].nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d world = ra * nodes.positions[i] + a.position;
    Eigen::Vector3d gradient;
    if (std::abs(levelSets.phi(b.shape, rb.transpose() * (world - b.position), gradient)) > touch) continue;
    visit(i, world, Eigen::Vector3d(ra * nodes.normals[i]), Eigen::Vector3d((rb * gradient).normalized()));
  }
}

// The nodes of body `from` touching body `to` face against face: the node's own normal opposes the
// other surface's (not an edge of one resting against the other's face, nor a node beside the
// contact), with `to`'s outward normal there (turned, if `flip`, so that it points from the pair's
// first body into its second).
void touchingNodes(const Bundle& bundle, const AssemblyLevelSets& levelSets, int from, int to, double touch, bool flip,
                   std::vector<TouchingNode>& out) {
  forTouchingNodes(bundle, levelSets, from, to, touch, [&](std::size_t, const Eigen::Vector3d& point, const Eigen::Vector3d& own, const Eigen::Vector3d& outward) {
    if (own.dot(outward) <= -kSameNormal) out.push_back({point, flip ? Eigen::Vector3d(-outward) : outward});
  });
}

}  // namespace

std::vector<ContactNode> contactNodes(const Bundle& bundle, const AssemblyLevelSets& levelSets, double touchDistance) {
  std::vector<ContactNode> springs;
  for (const auto& [a, b] : nearbyPairs(bundle, touchDistance)) {
    if (bundle.bodies[a].fixed && bundle.bodies[b].fixed) continue;
    for (const auto& [from, to] : {std::pair<int, int>{a, b}, std::pair<int, int>{b, a}}) {
      const SurfaceNodes& nodes = bundle.shapes[bundle.bodies[from].shape].nodes;
      forTouchingNodes(bundle, levelSets, from, to, touchDistance,
                       [&, a = a, b = b, from = from](std::size_t i, const Eigen::Vector3d& point, const Eigen::Vector3d& own, const Eigen::Vector3d& outward) {
                         const double area = 0.5 * nodes.areas[i] * std::max(0.0, -own.dot(outward));  // out of `to`
                         if (area > 0) springs.push_back({a, b, point, from == a ? Eigen::Vector3d(-outward) : outward, area});
                       });
    }
  }
  return springs;
}

std::vector<ContactCorner> contactPolygons(const Bundle& bundle, const AssemblyLevelSets& levelSets, double touchDistance) {
  std::vector<ContactCorner> corners;
  int polygons = 0;
  for (const auto& [a, b] : nearbyPairs(bundle, touchDistance)) {
    if (bundle.bodies[a].fixed && bundle.bodies[b].fixed) continue;
    std::vector<TouchingNode> nodes;
    touchingNodes(bundle, levelSets, a, b, touchDistance, true, nodes);   // b's normal points into a: turned
    touchingNodes(bundle, levelSets, b, a, touchDistance, false, nodes);  // a's normal points into b
    // Groups by normal, each led by its first node's normal.
    std::vector<std::vector<TouchingNode>> groups;
    for (const TouchingNode& node : nodes) {
      auto group = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.front().normal.dot(node.normal) >= kSameNormal; });
      if (group == groups.end()) groups.push_back({node});
      else group->push_back(node);
    }
    for (const auto& group : groups) {
      if (group.size() < 3) continue;
      Eigen::Vector3d normal(0, 0, 0), centre(0, 0, 0);
      for (const TouchingNode& node : group) {
        normal += node.normal;
        centre += node.point;
      }
      normal.normalize();
      centre /= static_cast<double>(group.size());
      const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
      std::vector<Eigen::Vector2d> plane;
      for (const TouchingNode& node : group) plane.emplace_back(u.dot(node.point - centre), v.dot(node.point - centre));
      const std::vector<Eigen::Vector2d> hull = simplified(convexHull(plane), kMostCorners);
      double extent = 0;
      for (const Eigen::Vector2d& x : plane) extent = std::max(extent, x.norm());
      if (hull.size() < 3 || polygonArea(hull) <= 1e-6 * extent * extent) continue;  // a line or a point
      for (const Eigen::Vector2d& x : hull) corners.push_back({a, b, centre + x.x() * u + x.y() * v, normal, polygons});
      ++polygons;
    }
  }
  return corners;
}

}  // namespace tessera

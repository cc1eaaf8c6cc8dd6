#include "solver/contact_bars.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace tessera {

ContactBars::ContactBars(const std::vector<TriangleMesh>& meshes, std::vector<int> shape,
                         std::vector<Eigen::Vector3d> position, std::vector<Eigen::Quaterniond> orientation,
                         std::vector<char> fixed)
    : shape_(std::move(shape)), position_(std::move(position)), orientation_(std::move(orientation)),
      fixed_(std::move(fixed)) {
  for (const TriangleMesh& mesh : meshes) {
    vertices_.push_back(mesh.vertices);
    double least = std::numeric_limits<double>::infinity();
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
      const Eigen::Vector3d n = triangleAreaVector(mesh, t);
      if (!(n.norm() > 0)) continue;
      double s = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& x : mesh.vertices) s = std::max(s, n.dot(x));
      least = std::min(least, s / n.norm());
    }
    shortestOfShape_.push_back(least);
  }
}

double ContactBars::support(int body, const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d local = orientation_[body].conjugate() * direction;
  double s = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& x : vertices_[shape_[body]]) s = std::max(s, local.dot(x));
  return s;
}

double ContactBars::betweenBodies(int a, int b) const {
  const Eigen::Vector3d d = position_[b] - position_[a];
  const double length = d.norm();
  // Two fixed bodies never meet in a run (the broad phase pairs none); two at one centroid have
  // no line between them: both count their shortest bars.
  if ((fixed_[a] && fixed_[b]) || !(length > 0)) return shortest(a) + shortest(b);
  const Eigen::Vector3d n = d / length;
  double sa = std::max(support(a, n), 0.0), sb = std::max(support(b, -n), 0.0);
  if (!(sa + sb > 0)) sa = sb = 1.0;  // neither reaches towards the other: half each
  const double wa = fixed_[a] ? 0.0 : std::max(length * sa / (sa + sb), shortest(a));
  const double wb = fixed_[b] ? 0.0 : std::max(length * sb / (sa + sb), shortest(b));
  return wa + wb;  // written alike for a and b: the same for (b, a)
}

double ContactBars::againstObstacle(int a, const Eigen::Vector3d& towards) const {
  return std::max(support(a, towards), shortest(a));  // a fixed body too: the obstacle is rigid
}

}  // namespace tessera

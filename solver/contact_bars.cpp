#include "solver/contact_bars.h"

#include "geometry/mesh_section.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace tessera {

namespace {

// m, max over the points of direction . x.
double supportOf(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& direction) {
  double s = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& x : points) s = std::max(s, direction.dot(x));
  return s;
}

// The distinct normals of a mesh's faces (triangles whose unit normals agree to 1e-9 are one
// face), the largest `count` by area.
std::vector<Eigen::Vector3d> largestFaceNormals(const TriangleMesh& mesh, int count) {
  std::vector<std::pair<Eigen::Vector3d, double>> faces;  // unit normal, area
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d v = triangleAreaVector(mesh, t);
    if (!(v.norm() > 0)) continue;
    const Eigen::Vector3d n = v.normalized();
    auto same = std::find_if(faces.begin(), faces.end(), [&](const auto& f) { return (f.first - n).norm() < 1e-9; });
    if (same == faces.end()) faces.emplace_back(n, 0.0), same = faces.end() - 1;
    same->second += 0.5 * v.norm();
  }
  std::stable_sort(faces.begin(), faces.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
  std::vector<Eigen::Vector3d> normals;
  for (int i = 0; i < std::min(count, static_cast<int>(faces.size())); ++i) normals.push_back(faces[i].first);
  return normals;
}

}  // namespace

ContactBars::ContactBars(const std::vector<TriangleMesh>& meshes, std::vector<int> shape,
                         std::vector<Eigen::Vector3d> position, std::vector<Eigen::Quaterniond> orientation,
                         std::vector<char> fixed, bool sections)
    : meshes_(meshes), sections_(sections), shape_(std::move(shape)), position_(std::move(position)),
      orientation_(std::move(orientation)), fixed_(std::move(fixed)) {
  for (int s = 0; s < static_cast<int>(meshes_.size()); ++s) {
    const TriangleMesh& mesh = meshes_[s];
    double least = std::numeric_limits<double>::infinity();
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
      const Eigen::Vector3d n = triangleAreaVector(mesh, t);
      if (n.norm() > 0) least = std::min(least, supportOf(mesh.vertices, n) / n.norm());
    }
    shortestOfShape_.push_back(least);
    double leastFactor = 1.0;
    if (sections_)
      for (const Eigen::Vector3d& n : largestFaceNormals(mesh, kBoundFaces))
        leastFactor = std::min(leastFactor, unboundedFactor(s, n));
    leastFactorOfShape_.push_back(leastFactor);
  }
}

double ContactBars::support(int body, const Eigen::Vector3d& direction) const {
  return supportOf(meshes_[shape_[body]].vertices, orientation_[body].conjugate() * direction);
}

double ContactBars::unboundedFactor(int shape, const Eigen::Vector3d& local) const {
  const TriangleMesh& mesh = meshes_[shape];
  Eigen::Vector3d facing = Eigen::Vector3d::Zero();  // the summed area vectors of the faces turned towards `local`
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d v = 0.5 * triangleAreaVector(mesh, t);
    if (v.dot(local) > kFacingCosine * v.norm()) facing += v;
  }
  const double contactArea = facing.norm();
  if (!(contactArea > 0)) return 1.0;
  const Eigen::Vector3d m = facing / contactArea;
  const double reach = supportOf(mesh.vertices, m);
  if (!(reach > 0)) return 1.0;
  double sum = 0.0;  // midpoint rule of int_0^reach A_c / A(y) dy / reach
  for (int i = 0; i < kSectionSamples; ++i) {
    const double area = sectionArea(mesh, m, (i + 0.5) * reach / kSectionSamples);
    sum += contactArea / std::max(area, 0.1 * contactArea);
  }
  return sum / kSectionSamples;
}

double ContactBars::sectionFactor(int shape, const Eigen::Vector3d& local) const {
  if (!sections_) return 1.0;
  return std::max(unboundedFactor(shape, local), leastFactorOfShape_[shape]);
}

double ContactBars::bar(int body, const Eigen::Vector3d& towards, double length) const {
  const double w = std::max(length, shortestOfShape_[shape_[body]]);
  return w * sectionFactor(shape_[body], orientation_[body].conjugate() * towards);
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
  const double wa = fixed_[a] ? 0.0 : bar(a, n, length * sa / (sa + sb));
  const double wb = fixed_[b] ? 0.0 : bar(b, -n, length * sb / (sa + sb));
  return wa + wb;  // written alike for a and b: the same for (b, a)
}

double ContactBars::againstObstacle(int a, const Eigen::Vector3d& towards) const {
  return bar(a, towards, support(a, towards));  // a fixed body too: the obstacle is rigid
}

}  // namespace tessera

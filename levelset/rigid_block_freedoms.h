#pragma once
// The rigid-block analyses' shared bookkeeping (docs/check.md): the free bodies' columns, a unit
// force's wrench on them, and a column vector read back as body motions. Private to levelset/.
#include "levelset/bundle.h"
#include "levelset/contact_polygons.h"
#include "levelset/rigid_block_analysis.h"

#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tessera::rigid_blocks {

constexpr double kMostFriction = 10;  // the highest friction coefficient the checks try

// The free bodies' degrees of freedom: body k's (v, L w) at columns 6 f(k) .. 6 f(k) + 5, with L
// the bodies' median size so that every column has the unit of a velocity.
struct Freedoms {
  std::vector<int> index;  // per body: its rank among the free bodies, or -1
  int count = 0;           // free bodies
  double length = 1;       // m, L
  std::vector<Eigen::Vector3d> position;  // m, per body: the point its rotation turns about

  Freedoms(const std::vector<Eigen::Vector3d>& bodyPosition, const std::vector<char>& fixed, double bodyLength)
      : length(bodyLength), position(bodyPosition) {
    for (char f : fixed) {
      index.push_back(f ? -1 : count);
      count += !f;
    }
  }
  explicit Freedoms(const Bundle& bundle) {
    std::vector<double> sizes;
    for (const Body& b : bundle.bodies) {
      index.push_back(b.fixed ? -1 : count);
      count += !b.fixed;
      position.push_back(b.position);
      sizes.push_back(boundingBox(bundle.shapes[b.shape].mesh.vertices).diagonal().norm());
    }
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    if (!sizes.empty()) length = sizes[sizes.size() / 2];
  }
};

// Each free body's weight in the columns' units, volume / L^3 (density and g factored out), at
// its column 6 f + 2 (the force along z).
inline Eigen::VectorXd weights(const Bundle& bundle, const Freedoms& freedoms) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(6 * freedoms.count);
  for (int body = 0; body < static_cast<int>(bundle.bodies.size()); ++body)
    if (freedoms.index[body] >= 0)
      w[6 * freedoms.index[body] + 2] = bundle.shapes[bundle.bodies[body].shape].mass.volume / std::pow(freedoms.length, 3);
  return w;
}

struct Entry {
  int column;
  double value;
};

// The wrench a unit force `direction` at `point` on the corner's bodies exerts on their freedoms:
// + on `second`, - on `first` (column, value), forces then moments / L. The same numbers are
// row c of A for the corner's normal: the relative normal velocity n . (u_2(p) - u_1(p)).
inline std::vector<Entry> wrench(const Freedoms& freedoms, const ContactCorner& c, const Eigen::Vector3d& direction) {
  std::vector<Entry> entries;
  for (const auto& [body, sign] : {std::pair<int, double>{c.second, 1.0}, std::pair<int, double>{c.first, -1.0}}) {
    const int k = freedoms.index[body];
    if (k < 0) continue;
    const Eigen::Vector3d moment = (c.point - freedoms.position[body]).cross(direction) / freedoms.length;
    for (int i = 0; i < 3; ++i) {  // rounding noise (1e-17 of a unit normal) left out: it only stalls the simplex
      if (std::abs(direction[i]) > 1e-12) entries.push_back({6 * k + i, sign * direction[i]});
      if (std::abs(moment[i]) > 1e-12) entries.push_back({6 * k + 3 + i, sign * moment[i]});
    }
  }
  return entries;
}

inline std::vector<BodyMotion> motionOf(const Freedoms& freedoms, const Eigen::VectorXd& x) {
  std::vector<BodyMotion> motion;
  const double largest = x.cwiseAbs().maxCoeff();
  if (!(largest > 0)) return motion;
  for (int body = 0; body < static_cast<int>(freedoms.index.size()); ++body) {
    const int k = freedoms.index[body];
    if (k < 0) continue;
    const Eigen::Matrix<double, 6, 1> u = x.segment<6>(6 * k) / largest;
    if (u.cwiseAbs().maxCoeff() < 1e-3) continue;
    motion.push_back({body, u.head<3>(), u.tail<3>()});
  }
  return motion;
}

}  // namespace tessera::rigid_blocks

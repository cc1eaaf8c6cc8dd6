#pragma once
#include "solver/obstacles.h"
#include "solver/rigid_bodies.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace tessera {

/// How far each body and each sphere has travelled, m, summed from one evaluation of the contacts
/// to the next: body i adds |p - p_last| + turnChord(q, q_last) r_i (r_i: the farthest point of
/// its shape from its centroid), a sphere |c - c_last|. Between any two evaluations no point of the
/// body moves farther than what its travel grew by (a point's displacement is at most the sum of
/// its moves, each at most |dp| + 2 sin(theta / 2) r). Taken from the poses themselves at each
/// evaluation, so a pose set between steps counts as well as a step's drift. The pairs use it to
/// skip their exact motion test while it cannot reach the rebuild threshold (beginEvaluation).
struct Travel {
  std::vector<double> body, sphere;  ///< m, since the first update
  std::vector<Eigen::Vector3d> lastPosition, lastCentre;
  std::vector<Eigen::Quaterniond> lastOrientation;

  /// Adds the moves since the last update; `radius`: r_i of each body. Starts at 0 for every body
  /// and sphere it has not seen.
  void update(const RigidBodies& bodies, const std::vector<double>& radius, const std::vector<SphereObstacle>& spheres) {
    if (body.size() != bodies.size()) {
      body.assign(bodies.size(), 0.0);
      lastPosition = bodies.position;
      lastOrientation = bodies.orientation;
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      body[i] += (bodies.position[i] - lastPosition[i]).norm() + turnChord(bodies.orientation[i], lastOrientation[i]) * radius[i];
      lastPosition[i] = bodies.position[i];
      lastOrientation[i] = bodies.orientation[i];
    }
    for (std::size_t k = sphere.size(); k < spheres.size(); ++k) {
      sphere.push_back(0.0);
      lastCentre.push_back(spheres[k].center);
    }
    for (std::size_t k = 0; k < spheres.size(); ++k) {
      sphere[k] += (spheres[k].center - lastCentre[k]).norm();
      lastCentre[k] = spheres[k].center;
    }
  }
};

}  // namespace tessera

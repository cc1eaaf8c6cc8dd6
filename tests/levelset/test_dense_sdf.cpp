// The dense sampler: trilinear interpolation reproduces linear fields exactly, with their gradient.
#include "levelset/dense_sdf.h"

#include <catch2/catch.hpp>

#include <random>

using namespace tessera;

namespace {

DenseSdf linearField(const Eigen::Vector3d& g, double c) {
  DenseSdf sdf;
  sdf.origin = Eigen::Vector3d(-0.3, 0.1, -0.2);
  sdf.voxelSize = 0.05;
  sdf.dims = {9, 7, 5};
  sdf.background = 10.0f;
  sdf.values.resize(9 * 7 * 5);
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 7; ++j)
      for (int k = 0; k < 5; ++k) sdf.values[sdf.index(i, j, k)] = static_cast<float>(g.dot(sdf.nodePosition(i, j, k)) + c);
  return sdf;
}

}  // namespace

TEST_CASE("trilinear sampling is exact for a linear field, value and gradient") {
  const Eigen::Vector3d g = Eigen::Vector3d(0.3, -0.8, 0.52).normalized();
  const DenseSdf sdf = linearField(g, 0.01);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int n = 0; n < 1000; ++n) {
    const Eigen::Vector3d x = sdf.origin + (sdf.upperCorner() - sdf.origin).cwiseProduct(Eigen::Vector3d(u(random), u(random), u(random)));
    const SdfSample s = sdf.sample(x);
    REQUIRE(s.phi == Approx(g.dot(x) + 0.01).margin(1e-6));
    REQUIRE((s.gradient - g).norm() < 1e-5);
  }
  // Grid nodes, including the upper corner, return the stored value.
  REQUIRE(sdf.sample(sdf.upperCorner()).phi == Approx(sdf.at(8, 6, 4)).margin(1e-7));
  REQUIRE(sdf.sample(sdf.origin).phi == Approx(sdf.at(0, 0, 0)).margin(1e-7));
}

TEST_CASE("outside the grid the value grows with the distance to the grid and points away") {
  const DenseSdf sdf = linearField(Eigen::Vector3d(0, 0, 1), 0.0);
  const Eigen::Vector3d corner = sdf.upperCorner();
  REQUIRE_FALSE(sdf.contains(corner + Eigen::Vector3d(0.1, 0, 0)));
  const SdfSample s = sdf.sample(corner + Eigen::Vector3d(0.1, 0, 0));
  REQUIRE(s.phi == Approx(sdf.at(8, 6, 4) + 0.1).margin(1e-6));
  REQUIRE((s.gradient - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
}

TEST_CASE("value() is sample().phi to the last bit, inside the grid and out") {
  const DenseSdf sdf = linearField(Eigen::Vector3d(0.6, 0.48, -0.64), 0.02);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-0.3, 1.3);  // a band beyond every side of the grid
  for (int n = 0; n < 2000; ++n) {
    const Eigen::Vector3d x = sdf.origin + (sdf.upperCorner() - sdf.origin).cwiseProduct(Eigen::Vector3d(u(random), u(random), u(random)));
    REQUIRE(sdf.value(x) == sdf.sample(x).phi);
  }
  REQUIRE(sdf.value(sdf.upperCorner()) == sdf.sample(sdf.upperCorner()).phi);
}

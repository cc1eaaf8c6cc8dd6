// Mass properties against closed-form values of polyhedra (1e-9 relative).
#include "geometry/block_generators.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_validation.h"
#include "tests/fixtures/analytic_meshes.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>

using namespace tessera;
using namespace tessera::test;

namespace {

constexpr double kRel = 1e-9;

// Inertia per unit density of an axis-aligned box of sides s about its centroid.
Eigen::Matrix3d boxInertia(const Eigen::Vector3d& s) {
  const double v = s.prod();
  return Eigen::Vector3d(v * (s.y() * s.y() + s.z() * s.z()) / 12, v * (s.x() * s.x() + s.z() * s.z()) / 12,
                         v * (s.x() * s.x() + s.y() * s.y()) / 12)
      .asDiagonal();
}

// Parallel-axis theorem: inertia about a point displaced by d from the centroid.
Eigen::Matrix3d shifted(const Eigen::Matrix3d& inertia, double volume, const Eigen::Vector3d& d) {
  return inertia + volume * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

void requireClose(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected, double scale) {
  INFO("actual\n" << actual << "\nexpected\n" << expected);
  REQUIRE((actual - expected).cwiseAbs().maxCoeff() <= kRel * scale);
}

MassProperties validated(TriangleMesh mesh) {
  validateSolidMesh(mesh, "fixture");
  return computeMassProperties(mesh);
}

}  // namespace

TEST_CASE("cube: volume, area, centroid and inertia are exact") {
  const double a = 2.0;
  const MassProperties p = validated(makeBox(a, a, a));
  REQUIRE(p.volume == Approx(a * a * a).epsilon(kRel));
  REQUIRE(p.surfaceArea == Approx(6 * a * a).epsilon(kRel));
  requireClose(p.centroid, Eigen::Vector3d::Zero(), a);
  requireClose(p.inertia, Eigen::Matrix3d::Identity() * std::pow(a, 5) / 6, std::pow(a, 5));
  // Three equal moments: the body axes stay the mesh axes.
  requireClose(p.principalAxes, Eigen::Matrix3d::Identity(), 1.0);
}

TEST_CASE("rectangular box off the origin: exact values, axes follow the mesh axes") {
  const Eigen::Vector3d sides(4.0, 2.0, 1.0), offset(3.0, -1.5, 7.25);
  const MassProperties p = validated(transformed(makeBox(4, 2, 1), Eigen::Matrix3d::Identity(), offset));
  REQUIRE(p.volume == Approx(8.0).epsilon(kRel));
  REQUIRE(p.surfaceArea == Approx(2 * (8 + 4 + 2)).epsilon(kRel));
  requireClose(p.centroid, offset, offset.norm());
  requireClose(p.inertia, boxInertia(sides), boxInertia(sides).maxCoeff());
  requireClose(p.principalMoments, boxInertia(sides).diagonal(), boxInertia(sides).maxCoeff());
  requireClose(p.principalAxes, Eigen::Matrix3d::Identity(), 1.0);
}

TEST_CASE("rotated box: principal frame recovers the rotation") {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.5, 0.25, -2.0);
  const Eigen::Vector3d sides(4.0, 2.0, 1.0);
  const MassProperties p = validated(transformed(makeBox(4, 2, 1), R, t));
  requireClose(p.centroid, t, 2.0);
  requireClose(p.inertia, R * boxInertia(sides) * R.transpose(), boxInertia(sides).maxCoeff());
  requireClose(p.principalMoments, boxInertia(sides).diagonal(), boxInertia(sides).maxCoeff());
  // Each body axis is the rotated mesh axis, up to sign.
  for (int k = 0; k < 3; ++k) REQUIRE(std::abs(p.principalAxes.col(k).dot(R.col(k))) == Approx(1.0).epsilon(kRel));
  REQUIRE(p.principalAxes.determinant() == Approx(1.0).epsilon(kRel));
}

TEST_CASE("octahedron (sphere-like, convex): exact volume and inertia") {
  const double r = 1.5;
  const MassProperties p = validated(octahedron(r));
  REQUIRE(p.volume == Approx(4 * r * r * r / 3).epsilon(kRel));
  // Eight equilateral faces of side r sqrt(2).
  REQUIRE(p.surfaceArea == Approx(8 * std::sqrt(3.0) / 4 * 2 * r * r).epsilon(kRel));
  requireClose(p.centroid, Eigen::Vector3d::Zero(), r);
  requireClose(p.inertia, Eigen::Matrix3d::Identity() * 4 * std::pow(r, 5) / 15, std::pow(r, 5));
}

TEST_CASE("icosphere: volume and inertia equal the sum over its pyramids from the centre") {
  const TriangleMesh mesh = icosphere(1.0, 3);
  const MassProperties p = validated(mesh);
  // Independent closed form per face: a tetrahedron (0, a, b, c) has volume a.(b x c)/6 and
  // second moment V/20 (sum v v^T + s s^T) (Tonon 2005); the solid is the union of these pyramids.
  double volume = 0;
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const double v = std::abs(a.dot(b.cross(c))) / 6;
    const Eigen::Vector3d s = a + b + c;
    volume += v;
    second += v / 20 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  REQUIRE(p.volume == Approx(volume).epsilon(kRel));
  REQUIRE(volume < 4 * M_PI / 3);
  requireClose(p.centroid, Eigen::Vector3d::Zero(), 1.0);
  requireClose(p.inertia, second.trace() * Eigen::Matrix3d::Identity() - second, 1.0);
}

TEST_CASE("L-shaped prism (non-convex): exact values from its two boxes") {
  const double s = 0.5;
  const MassProperties p = validated(lPrism(s));
  // Box A = [0,2]x[0,1]x[0,1], box B = [0,1]x[1,2]x[0,1], scaled by s.
  const Eigen::Vector3d sizeA = s * Eigen::Vector3d(2, 1, 1), sizeB = s * Eigen::Vector3d(1, 1, 1);
  const Eigen::Vector3d cA = s * Eigen::Vector3d(1, 0.5, 0.5), cB = s * Eigen::Vector3d(0.5, 1.5, 0.5);
  const double vA = sizeA.prod(), vB = sizeB.prod(), v = vA + vB;
  const Eigen::Vector3d c = (vA * cA + vB * cB) / v;
  const Eigen::Matrix3d inertia = shifted(boxInertia(sizeA), vA, cA - c) + shifted(boxInertia(sizeB), vB, cB - c);
  REQUIRE(p.volume == Approx(v).epsilon(kRel));
  REQUIRE(p.surfaceArea == Approx(s * s * (2 * 3 + 8)).epsilon(kRel));
  requireClose(p.centroid, c, s);
  requireClose(p.inertia, inertia, inertia.maxCoeff());
  // Principal frame diagonalises the inertia tensor.
  const Eigen::Matrix3d diagonal = p.principalAxes.transpose() * p.inertia * p.principalAxes;
  requireClose(diagonal, Eigen::Matrix3d(p.principalMoments.asDiagonal()), inertia.maxCoeff());
}

TEST_CASE("planar TIS block: volume a^2 h - h^3 tan^2(theta) / 3, centroid at the origin") {
  const double a = 10e-3, h = 3.18e-3, theta = 5 * M_PI / 180;
  const MassProperties p = validated(makePlanarBlock(a, h, theta));
  REQUIRE(p.volume == Approx(a * a * h - std::pow(h, 3) * std::pow(std::tan(theta), 2) / 3).epsilon(kRel));
  requireClose(p.centroid, Eigen::Vector3d::Zero(), a);
  // Square symmetry: equal moments about x and y; the body frame is the mesh frame.
  REQUIRE(p.principalMoments.x() == Approx(p.principalMoments.y()).epsilon(kRel));
  requireClose(p.principalAxes, Eigen::Matrix3d::Identity(), 1e-6);
}

TEST_CASE("toBodyFrame puts the centroid at the origin and diagonalises the inertia") {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 0.2).normalized()).toRotationMatrix();
  TriangleMesh mesh = transformed(lPrism(1.0), R, Eigen::Vector3d(5, 6, 7));
  validateSolidMesh(mesh, "fixture");
  const MassProperties p = computeMassProperties(mesh);
  const MassProperties body = computeMassProperties(toBodyFrame(mesh, p));
  requireClose(body.centroid, Eigen::Vector3d::Zero(), 10.0);
  requireClose(body.inertia, Eigen::Matrix3d(p.principalMoments.asDiagonal()), p.principalMoments.maxCoeff());
  REQUIRE(body.volume == Approx(p.volume).epsilon(kRel));
}

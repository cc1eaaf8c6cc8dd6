// Generated blocks are valid solids with the closed-form volume; the shipped default block
// is the generator's planar block.
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_validation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace tessera;

TEST_CASE("planar block: valid, closed-form volume, faces inclined by theta") {
  for (double degrees : {0.0, 5.0, 12.0}) {
    const double a = 10, h = 3.18, theta = degrees * M_PI / 180;
    TriangleMesh block = makePlanarBlock(a, h, theta);
    REQUIRE_FALSE(validateSolidMesh(block, "planar").reoriented);
    REQUIRE(signedVolume(block) == Approx(a * a * h - h * h * h * std::pow(std::tan(theta), 2) / 3).epsilon(1e-12));
    // Top face: wider in x, narrower in y, by h tan(theta).
    const Eigen::AlignedBox3d box = boundingBox(block.vertices);
    REQUIRE(box.sizes().x() == Approx(a + h * std::tan(theta)).epsilon(1e-12));
    REQUIRE(box.sizes().z() == Approx(h).epsilon(1e-12));
  }
  REQUIRE_THROWS_AS(makePlanarBlock(1, 3, 80 * M_PI / 180), InputError);
  REQUIRE_THROWS_AS(makeBox(1, 0, 1), InputError);
}

TEST_CASE("the default block in assets/ is the generator's planar block (a 10, h 3.18, 5 deg)") {
  MeshImportOptions options;
  options.metresPerUnit = 1e-3;
  const ImportedMesh asset = importMesh(TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj", options);
  const TriangleMesh generated = makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180);
  REQUIRE(asset.mesh.triangles.size() == generated.triangles.size());
  for (int t = 0; t < static_cast<int>(generated.triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) REQUIRE((triangleCorner(asset.mesh, t, k) - triangleCorner(generated, t, k)).norm() < 1e-9);
}

namespace {

// Prismatoid (Simpson) volume of a solid whose horizontal cross-section area is quadratic in z
// within [z0, z1]: V = (z1 - z0) / 6 (A(z0) + 4 A(zm) + A(z1)). Cross-sections come from the mesh
// itself: the polygon where the plane z cuts the lateral faces, by the shoelace formula.
double crossSectionArea(const TriangleMesh& mesh, double z) {
  // For these generators the cross-section is convex: take the hull of the edge-plane crossings.
  std::vector<Eigen::Vector2d> points;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = mesh.vertices[t[k]], b = mesh.vertices[t[(k + 1) % 3]];
      if ((a.z() - z) * (b.z() - z) <= 0 && a.z() != b.z()) {
        const double w = (z - a.z()) / (b.z() - a.z());
        points.push_back(((1 - w) * a + w * b).head<2>());
      }
    }
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : points) c += p / static_cast<double>(points.size());
  std::sort(points.begin(), points.end(), [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return std::atan2(p.y() - c.y(), p.x() - c.x()) < std::atan2(q.y() - c.y(), q.x() - c.x());
  });
  double area = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const auto& q = points[(i + 1) % points.size()];
    area += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  return area;
}

double prismatoidVolume(const TriangleMesh& mesh, const std::vector<double>& levels) {
  double v = 0;
  for (std::size_t i = 0; i + 1 < levels.size(); ++i) {
    const double z0 = levels[i], z1 = levels[i + 1], e = 1e-12 * (z1 - z0);
    v += (z1 - z0) / 6 *
         (crossSectionArea(mesh, z0 + e) + 4 * crossSectionArea(mesh, 0.5 * (z0 + z1)) + crossSectionArea(mesh, z1 - e));
  }
  return v;
}

std::vector<double> evenLevels(double h, int n) {
  std::vector<double> z;
  for (int k = 0; k <= n; ++k) z.push_back(-0.5 * h + h * k / n);
  return z;
}

}  // namespace

TEST_CASE("hex block: valid, prismatoid volume, alternating faces") {
  const double r = 5, h = 3.18, theta = 5 * M_PI / 180;
  TriangleMesh hex = makeHexBlock(r, h, theta);
  REQUIRE_FALSE(validateSolidMesh(hex, "hex").reoriented);
  REQUIRE(signedVolume(hex) == Approx(prismatoidVolume(hex, evenLevels(h, 1))).epsilon(1e-9));
  // Mid-height: a regular hexagon of inradius r, area 2 sqrt(3) r^2.
  REQUIRE(crossSectionArea(hex, 0.0) == Approx(2 * std::sqrt(3.0) * r * r).epsilon(1e-12));
  // Each lateral face lies in its plane n_k . x = r + (-1)^k z tan(theta).
  for (const auto& v : hex.vertices) {
    int onFaces = 0;
    for (int k = 0; k < 6; ++k) {
      const Eigen::Vector2d n(std::cos(M_PI / 3 * k), std::sin(M_PI / 3 * k));
      const double d = r + (k % 2 == 0 ? 1 : -1) * v.z() * std::tan(theta);
      onFaces += std::abs(n.dot(v.head<2>()) - d) < 1e-12;
    }
    REQUIRE(onFaces == 2);
  }
  REQUIRE_THROWS_AS(makeHexBlock(1, 3, 30 * M_PI / 180), InputError);
}

TEST_CASE("wave block: valid, exact polyhedron volume, converges to the smooth volume") {
  const double a = 10, h = 3.18, theta = 5 * M_PI / 180, amplitude = 0.2;
  for (int waves : {1, 2}) {
    const int levels = 24 * waves;
    TriangleMesh wave = makeWaveBlock(a, h, theta, amplitude, waves, levels);
    REQUIRE_FALSE(validateSolidMesh(wave, "wave").reoriented);
    REQUIRE(signedVolume(wave) == Approx(prismatoidVolume(wave, evenLevels(h, levels))).epsilon(1e-9));
    // Smooth surface: a^2 h - 4 integral f^2, f = z tan(theta) + A sin(2 pi n z / h):
    // integral f^2 = tan^2 h^3 / 12 - tan A (-1)^n h^2 / (pi n) + A^2 h / 2.
    const double t = std::tan(theta), sign = waves % 2 ? -1.0 : 1.0;
    const double f2 = t * t * h * h * h / 12 - t * amplitude * sign * h * h / (M_PI * waves) + amplitude * amplitude * h / 2;
    const double smooth = a * a * h - 4 * f2;
    const double fine = signedVolume(makeWaveBlock(a, h, theta, amplitude, waves, 400));
    REQUIRE(fine == Approx(smooth).epsilon(1e-6));
  }
  // With amplitude 0 it is the planar block.
  REQUIRE(signedVolume(makeWaveBlock(a, h, theta, 0.0, 1, 3)) == Approx(signedVolume(makePlanarBlock(a, h, theta))).epsilon(1e-12));
  REQUIRE_THROWS_AS(makeWaveBlock(a, h, theta, 6.0, 1, 24), InputError);
  REQUIRE_THROWS_AS(makeWaveBlock(a, h, theta, 0.2, 2, 4), InputError);
}

TEST_CASE("osteomorphic block: valid, volume a b h exactly, x-faces that match a copy moved by a") {
  const double a = 10, b = 8, h = 3.18, amplitude = 0.8;
  const int segments = 12;
  TriangleMesh block = makeOsteomorphicBlock(a, b, h, amplitude, 0.0, segments);
  REQUIRE_FALSE(validateSolidMesh(block, "osteomorphic").reoriented);
  // Every chord along x is a long: the volume is a b h whatever the surface.
  REQUIRE(signedVolume(block) == Approx(a * b * h).epsilon(1e-12));
  // The bulge peaks at y = b/4, z = 0 (a grid point: 2 x 12 segments along y, 12 along z).
  const Eigen::AlignedBox3d box = boundingBox(block.vertices);
  REQUIRE(box.max().x() == Approx(0.5 * a + amplitude).epsilon(1e-12));
  REQUIRE(box.min().x() == Approx(-0.5 * a - amplitude).epsilon(1e-12));
  REQUIRE(box.sizes().y() == Approx(b).epsilon(1e-12));
  REQUIRE(box.sizes().z() == Approx(h).epsilon(1e-12));
  // The copy moved by a along x touches face to face: each x+ vertex is an x- vertex moved by a,
  // and each vertex off the x-faces lies on a flat face (|y| = b/2 or |z| = h/2).
  std::vector<Eigen::Vector3d> left, right;
  for (const Eigen::Vector3d& v : block.vertices) {
    const bool flat = std::abs(std::abs(v.y()) - 0.5 * b) < 1e-12 || std::abs(std::abs(v.z()) - 0.5 * h) < 1e-12;
    if (!flat) (v.x() > 0 ? right : left).push_back(v);
    if (flat) REQUIRE(std::abs(std::abs(v.x()) - 0.5 * a) < 1e-12);
  }
  REQUIRE(left.size() == right.size());
  // The grid's interior points and the middles of its quads (2 x 12 by 12).
  REQUIRE(left.size() == static_cast<std::size_t>((2 * segments - 1) * (segments - 1) + 2 * segments * segments));
  for (const Eigen::Vector3d& v : left) {
    const Eigen::Vector3d moved = v + Eigen::Vector3d(a, 0, 0);
    REQUIRE(std::any_of(right.begin(), right.end(), [&](const Eigen::Vector3d& w) { return (w - moved).norm() < 1e-12; }));
  }
  // Amplitude 0 is the box.
  REQUIRE(signedVolume(makeOsteomorphicBlock(a, b, h, 0.0, 0.0, 2)) == Approx(signedVolume(makeBox(a, b, h))).epsilon(1e-12));
  REQUIRE_THROWS_AS(makeOsteomorphicBlock(a, b, h, 5.0, 0.0, 12), InputError);
  REQUIRE_THROWS_AS(makeOsteomorphicBlock(a, b, h, 0.8, 0.0, 1), InputError);
}

TEST_CASE("osteomorphic block curved both ways: valid, volume a b h exactly, y-faces that match a copy moved by b") {
  const double a = 10, b = 8, h = 3.18, amplitude = 0.8, amplitudeY = -0.5;
  const int segments = 6;
  TriangleMesh block = makeOsteomorphicBlock(a, b, h, amplitude, amplitudeY, segments);
  REQUIRE_FALSE(validateSolidMesh(block, "osteomorphic").reoriented);
  REQUIRE(signedVolume(block) == Approx(a * b * h).epsilon(1e-12));
  const Eigen::AlignedBox3d box = boundingBox(block.vertices);
  REQUIRE(box.sizes().x() == Approx(a + 2 * amplitude).epsilon(1e-12));
  REQUIRE(box.sizes().y() == Approx(b + 2 * std::abs(amplitudeY)).epsilon(1e-12));
  REQUIRE(box.sizes().z() == Approx(h).epsilon(1e-12));
  // Each vertex of the y+ face's interior is one of the y- face's moved by b.
  // (A vertex of an x-face lies on x = +-a/2 + A sin(2 pi y / b) cos(pi z / h).)
  const auto onXFace = [&](const Eigen::Vector3d& v) {
    return std::abs(std::abs(v.x() - amplitude * std::sin(2 * M_PI * v.y() / b) * std::cos(M_PI * v.z() / h)) - 0.5 * a) < 1e-9;
  };
  std::vector<Eigen::Vector3d> front, back;
  for (const Eigen::Vector3d& v : block.vertices)
    if (std::abs(v.y()) >= 0.5 * b - std::abs(amplitudeY) - 1e-9 && !onXFace(v) && std::abs(std::abs(v.z()) - 0.5 * h) > 1e-9)
      (v.y() > 0 ? back : front).push_back(v);
  // The grid's interior points and the middles of its quads (2 x 6 by 6).
  REQUIRE(front.size() == static_cast<std::size_t>((2 * segments - 1) * (segments - 1) + 2 * segments * segments));
  REQUIRE(back.size() == front.size());
  for (const Eigen::Vector3d& v : front) {
    const Eigen::Vector3d moved = v + Eigen::Vector3d(0, b, 0);
    REQUIRE(std::any_of(back.begin(), back.end(), [&](const Eigen::Vector3d& w) { return (w - moved).norm() < 1e-12; }));
  }
  // Faces steep enough to cross at the corner edges are refused: (2 pi A / b)(2 pi A_y / a) >= 1.
  REQUIRE_THROWS_AS(makeOsteomorphicBlock(a, b, h, 2.0, 1.5, segments), InputError);
}

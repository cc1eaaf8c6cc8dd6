// Generated tilings: tiles meet edge to edge; their tilted blocks are valid solids that share
// each edge's face plane and do not overlap; the square tiling gives the paper's planar block.
#include "geometry/block_generators.h"
#include "geometry/convex_planes.h"
#include "geometry/convex_polyhedron.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_validation.h"
#include "geometry/tilted_blocks.h"
#include "io/input_error.h"
#include "tests/fixtures/analytic_meshes.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

using namespace tessera;

namespace {

struct GeneratedBlocks {
  PlaneTiling tiling;
  std::vector<std::vector<EdgeNeighbour>> across;
  std::vector<std::vector<int>> tilts;
  std::vector<TriangleMesh> meshes;
};

GeneratedBlocks generate(const std::string& kind, double pitch, double thickness, double angle, const BaseSurface& surface = {}) {
  GeneratedBlocks g;
  TilingOptions options;
  options.kind = kind;
  options.pitch = pitch;
  options.columns = options.rows = 5;
  g.tiling = makeTiling(options);
  g.across = edgeNeighbours(g.tiling, 1e-9 * pitch);
  g.tilts = interlockingTilts(g.tiling, g.across, angle);
  const auto cuts = cornerCuts(g.tiling, g.across, g.tilts, thickness, angle);
  for (std::size_t t = 0; t < g.tiling.tiles.size(); ++t)
    g.meshes.push_back(tiltedBlock(g.tiling.tiles[t], g.tilts[t], cuts[t], thickness, angle, surface));
  return g;
}

// The volume two convex blocks share (0 when they do not overlap).
double sharedVolume(const TriangleMesh& a, const TriangleMesh& b, double size) {
  std::vector<FacePlane> planes = fitConvexPolyhedron(a)->planes;
  const std::vector<FacePlane> other = fitConvexPolyhedron(b)->planes;
  planes.insert(planes.end(), other.begin(), other.end());
  try {
    return signedVolume(convexPolyhedronFromPlanes(planes, size));
  } catch (const InputError&) {
    return 0;
  }
}

}  // namespace

TEST_CASE("convex polyhedron from planes: a box and a tetrahedron, closed and outward") {
  const std::vector<FacePlane> box{{{1, 0, 0}, 1}, {{-1, 0, 0}, 1}, {{0, 1, 0}, 2}, {{0, -1, 0}, 2}, {{0, 0, 1}, 3}, {{0, 0, -1}, 3}, {{1, 0, 0}, 1}};
  TriangleMesh mesh = convexPolyhedronFromPlanes(box, 10);
  REQUIRE_FALSE(validateSolidMesh(mesh, "box").reoriented);
  REQUIRE(signedVolume(mesh) == Approx(2 * 4 * 6).epsilon(1e-12));
  REQUIRE(mesh.vertices.size() == 8);
  const std::vector<FacePlane> tetrahedron{{{0, 0, -1}, 0}, {{-1, 0, 0}, 0}, {{0, -1, 0}, 0}, {Eigen::Vector3d(1, 1, 1).normalized(), 1 / std::sqrt(3.0)}};
  REQUIRE(signedVolume(convexPolyhedronFromPlanes(tetrahedron, 2)) == Approx(1.0 / 6).epsilon(1e-12));
  REQUIRE_THROWS_AS(convexPolyhedronFromPlanes({{{0, 0, 1}, 0}, {{0, 0, -1}, -1}}, 1), InputError);
}

TEST_CASE("tilings: edge to edge, tiles of the stated pitch, centred") {
  for (const std::string& kind : tilingKinds()) {
    TilingOptions options;
    options.kind = kind;
    options.pitch = 0.01;
    options.columns = options.rows = 5;
    const PlaneTiling tiling = makeTiling(options);
    const auto across = edgeNeighbours(tiling, 1e-9);
    Eigen::Vector2d mean(0, 0);
    int shared = 0;
    for (std::size_t t = 0; t < tiling.tiles.size(); ++t) {
      REQUIRE(polygonArea(tiling.tiles[t]) > 0);
      mean += polygonCentroid(tiling.tiles[t]);
      for (const EdgeNeighbour& e : across[t]) {
        if (e.tile < 0) continue;
        ++shared;
        REQUIRE(across[e.tile][e.edge].tile == static_cast<int>(t));
        if (kind != "voronoi")  // neighbouring centres one pitch apart
          REQUIRE((polygonCentroid(tiling.tiles[e.tile]) - polygonCentroid(tiling.tiles[t])).norm() == Approx(0.01).epsilon(1e-9));
      }
    }
    INFO(kind);
    REQUIRE(mean.norm() < 1e-12);
    REQUIRE(shared > static_cast<int>(tiling.tiles.size()));
  }
}

TEST_CASE("tilted blocks of every tiling: valid, faces shared across edges, no overlap") {
  const double pitch = 0.01, h = 0.00318;
  for (const std::string& kind : tilingKinds())
    for (double degrees : {0.0, 5.0, 20.0}) {
      INFO(kind << " at " << degrees << " degrees");
      const GeneratedBlocks g = generate(kind, pitch, h, degrees * M_PI / 180);
      const int count = static_cast<int>(g.meshes.size());
      for (int t = 0; t < count; ++t) {
        TriangleMesh copy = g.meshes[t];
        REQUIRE_FALSE(validateSolidMesh(copy, g.tiling.names[t]).reoriented);
        // Across a shared edge the signs are opposite: the two faces are one plane.
        for (std::size_t k = 0; k < g.across[t].size(); ++k) {
          const EdgeNeighbour& e = g.across[t][k];
          if (e.tile >= 0) REQUIRE(g.tilts[t][k] == -g.tilts[e.tile][e.edge]);
        }
        for (int u = t + 1; u < count; ++u) {
          const Eigen::Vector2d ct = polygonCentroid(g.tiling.tiles[t]), cu = polygonCentroid(g.tiling.tiles[u]);
          if ((ct - cu).norm() > 3 * pitch) continue;
          INFO(g.tiling.names[t] << " and " << g.tiling.names[u]);
          REQUIRE(sharedVolume(g.meshes[t], g.meshes[u], 10 * pitch) <= 1e-9 * pitch * pitch * h);
        }
      }
      // Each shared edge's plane carries a face of both blocks.
      if (degrees == 0) continue;
      for (int t = 0; t < count; ++t)
        for (std::size_t k = 0; k < g.across[t].size(); ++k) {
          const EdgeNeighbour& e = g.across[t][k];
          if (e.tile < 0) continue;
          const auto& p = g.tiling.tiles[t];
          const Eigen::Vector2d d = (p[(k + 1) % p.size()] - p[k]).normalized(), m(d.y(), -d.x());
          const double theta = degrees * M_PI / 180;
          const Eigen::Vector3d n(m.x() * std::cos(theta), m.y() * std::cos(theta), -g.tilts[t][k] * std::sin(theta));
          const double offset = m.dot(p[k]) * std::cos(theta);
          const auto cornersOnPlane = [&](const TriangleMesh& mesh) {
            return std::count_if(mesh.vertices.begin(), mesh.vertices.end(),
                                 [&](const Eigen::Vector3d& x) { return std::abs(n.dot(x) - offset) <= 1e-9 * pitch; });
          };
          REQUIRE(cornersOnPlane(g.meshes[t]) >= 3);
          REQUIRE(cornersOnPlane(g.meshes[e.tile]) >= 3);
        }
    }
}

TEST_CASE("the square tiling's tilted block is the paper's planar block, turned in a checkerboard") {
  const double pitch = 0.01, h = 0.00318, theta = 5 * M_PI / 180;
  const GeneratedBlocks g = generate("square", pitch, h, theta);
  const double expected = signedVolume(makePlanarBlock(pitch, h, theta));
  for (std::size_t t = 0; t < g.meshes.size(); ++t) {
    REQUIRE(signedVolume(g.meshes[t]) == Approx(expected).epsilon(1e-12));
    // Neighbours are turned: one's top face is longer in x, the other's in y.
    const auto topLongerInX = [&](std::size_t b) {
      Eigen::AlignedBox3d top;
      for (const Eigen::Vector3d& x : g.meshes[b].vertices)
        if (x.z() > 0) top.extend(x);
      return top.sizes().x() > top.sizes().y();
    };
    for (const EdgeNeighbour& e : g.across[t])
      if (e.tile >= 0) REQUIRE(topLongerInX(e.tile) != topLongerInX(t));
  }
}

TEST_CASE("tilted blocks: every tile of a tiling that allows it has faces leaning both ways") {
  for (const std::string& kind : tilingKinds()) {
    const GeneratedBlocks g = generate(kind, 0.01, 0.00318, 5 * M_PI / 180);
    for (std::size_t t = 0; t < g.tilts.size(); ++t) {
      bool out = false, in = false, interior = true;
      for (std::size_t k = 0; k < g.tilts[t].size(); ++k) {
        if (g.across[t][k].tile < 0) interior = false;
        else (g.tilts[t][k] > 0 ? out : in) = true;
      }
      INFO(kind << " tile " << g.tiling.names[t]);
      if (interior) REQUIRE((out && in));
    }
  }
}

TEST_CASE("a block among still neighbours is held against every translation by faces that lean both ways enough") {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<EdgeNeighbour> all(4, EdgeNeighbour{0, 0});
  REQUIRE(heldByNeighbours(square, {1, -1, 1, -1}, all));       // the checkerboard
  REQUIRE_FALSE(heldByNeighbours(square, {1, 1, 1, 1}, all));   // rests on all four: lifts off
  REQUIRE_FALSE(heldByNeighbours(square, {1, 1, -1, -1}, all)); // slides along (1, -1, 1)
  std::vector<EdgeNeighbour> open = all;
  open[2].tile = -1;  // no neighbour over one edge: it leaves that way
  REQUIRE_FALSE(heldByNeighbours(square, {1, -1, 1, -1}, open));
  std::vector<Eigen::Vector2d> pentagon, triangle;
  for (int k = 0; k < 5; ++k) pentagon.emplace_back(std::cos(2 * M_PI * k / 5), std::sin(2 * M_PI * k / 5));
  for (int k = 0; k < 3; ++k) triangle.emplace_back(std::cos(2 * M_PI * k / 3), std::sin(2 * M_PI * k / 3));
  const std::vector<EdgeNeighbour> five(5, EdgeNeighbour{0, 0}), three(3, EdgeNeighbour{0, 0});
  REQUIRE_FALSE(heldByNeighbours(pentagon, {-1, 1, 1, 1, 1}, five));  // one face in, the rest out (docs/tiling.md)
  REQUIRE(heldByNeighbours(pentagon, {1, -1, 1, -1, -1}, five));
  for (const std::vector<int>& signs : std::vector<std::vector<int>>{{1, 1, -1}, {1, -1, -1}, {1, 1, 1}})
    REQUIRE_FALSE(heldByNeighbours(triangle, signs, three));  // Gordan: never (docs/tiling.md)
}

TEST_CASE("tilted blocks: every free tile is held by its neighbours, in every tiling but the triangles") {
  for (const std::string& kind : tilingKinds()) {
    const GeneratedBlocks g = generate(kind, 0.01, 0.00318, 5 * M_PI / 180);
    int free = 0, held = 0;
    for (std::size_t t = 0; t < g.tilts.size(); ++t) {
      if (!freeTile(g.across[t])) continue;
      ++free;
      held += heldByNeighbours(g.tiling.tiles[t], g.tilts[t], g.across[t]) ? 1 : 0;
    }
    INFO(kind << ": " << held << " of " << free << " free tiles held");
    REQUIRE(free > 0);
    REQUIRE(held == (kind == "triangle" ? 0 : free));
  }
}

TEST_CASE("tilted blocks on a sphere and a cylinder: a dome and a vault without overlap, flat as the radius grows") {
  const double pitch = 0.01, h = 0.00318, theta = 5 * M_PI / 180;
  // A chord's midpoint normal is perpendicular to the chord (so the face contains the chord).
  for (const BaseSurface& surface : {baseSurface("sphere", 0.1), baseSurface("cylinder", 0.1)}) {
    const Eigen::Vector3d a = surface.point({0.01, -0.02}), b = surface.point({-0.015, 0.03});
    REQUIRE(std::abs(surface.normal(0.5 * (a + b)).dot(b - a)) < 1e-15);
  }
  REQUIRE_THROWS_AS(baseSurface("sphere", 0), InputError);
  REQUIRE_THROWS_AS(baseSurface("torus", 1), InputError);
  REQUIRE_THROWS_AS(baseSurface("sphere", 0.01).point({0.02, 0}), InputError);
  // A sphere a thousand times the slab is the plane to 1e-5 of a block's volume.
  const GeneratedBlocks flat = generate("hex", pitch, h, theta), far = generate("hex", pitch, h, theta, baseSurface("sphere", 50));
  for (std::size_t t = 0; t < flat.meshes.size(); ++t)
    REQUIRE(signedVolume(far.meshes[t]) == Approx(signedVolume(flat.meshes[t])).epsilon(1e-5));
  for (const BaseSurface& surface : {baseSurface("sphere", 0.6), baseSurface("cylinder", 0.6)})
    for (const std::string kind : {"hex", "square"}) {
      INFO(kind);
      const GeneratedBlocks g = generate(kind, pitch, h, theta, surface);
      for (std::size_t t = 0; t < g.meshes.size(); ++t) {
        TriangleMesh copy = g.meshes[t];
        REQUIRE_FALSE(validateSolidMesh(copy, g.tiling.names[t]).reoriented);
        for (std::size_t u = t + 1; u < g.meshes.size(); ++u)
          if ((polygonCentroid(g.tiling.tiles[t]) - polygonCentroid(g.tiling.tiles[u])).norm() < 2 * pitch)
            REQUIRE(sharedVolume(g.meshes[t], g.meshes[u], 10 * pitch) <= 1e-6 * pitch * pitch * h);
      }
    }
}

namespace {

// An OBJ of the height field z(x, y) on an n x n grid of squares (two triangles each) over
// [-half, half]^2, its triangles facing up (or down); yUp: written y-up, (x, z, -y).
std::string heightFieldObj(int n, double half, double (*z)(double, double), bool down = false, bool yUp = false) {
  std::string text;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -half + 2 * half * i / n, y = -half + 2 * half * j / n;
      text += "v " + std::to_string(x) + " " + (yUp ? std::to_string(z(x, y)) + " " + std::to_string(-y) : std::to_string(y) + " " + std::to_string(z(x, y))) + "\n";
    }
  const auto at = [n](int i, int j) { return std::to_string(j * (n + 1) + i + 1); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::string a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      text += down ? "f " + a + " " + c + " " + b + "\nf " + a + " " + d + " " + c + "\n"
                   : "f " + a + " " + b + " " + c + "\nf " + a + " " + c + " " + d + "\n";
    }
  return text;
}

}  // namespace

TEST_CASE("tilted blocks on a mesh surface: a flat mesh gives the plane's blocks, a fine spherical cap the sphere's, without overlap") {
  const double pitch = 0.01, h = 0.00318, theta = 5 * M_PI / 180;
  test::TempDir dir;
  test::writeFile(dir / "flat.obj", heightFieldObj(2, 0.05, [](double, double) { return 0.0; }));
  const GeneratedBlocks plane = generate("hex", pitch, h, theta), flat = generate("hex", pitch, h, theta, baseSurface(dir / "flat.obj", 0, 1.0));
  for (std::size_t t = 0; t < plane.meshes.size(); ++t) {
    REQUIRE(flat.meshes[t].vertices.size() == plane.meshes[t].vertices.size());
    for (std::size_t v = 0; v < plane.meshes[t].vertices.size(); ++v)
      REQUIRE((flat.meshes[t].vertices[v] - plane.meshes[t].vertices[v]).norm() < 1e-12 * pitch);
  }
  // A cap of the 0.6 m sphere on a 0.625 mm grid (its chords' sag 8e-8 m): the sphere's blocks to
  // 1e-3 of their volume, the file in millimetres and facing down (turned up on reading).
  test::writeFile(dir / "cap.obj", heightFieldObj(160, 50, [](double x, double y) { return std::sqrt(600.0 * 600 - x * x - y * y) - 600; }, true));
  const BaseSurface cap = baseSurface(dir / "cap.obj", 0, 1e-3);
  REQUIRE(cap.normal(cap.point({0.02, -0.01})).z() > 0);
  // The same cap written y-up and read with up = y: the same surface.
  test::writeFile(dir / "cap_yup.obj", heightFieldObj(160, 50, [](double x, double y) { return std::sqrt(600.0 * 600 - x * x - y * y) - 600; }, true, true));
  const BaseSurface capUp = baseSurface(dir / "cap_yup.obj", 0, 1e-3, "y");
  for (const Eigen::Vector2d& at : {Eigen::Vector2d(0.02, -0.01), Eigen::Vector2d(-0.03, 0.025), Eigen::Vector2d(0, 0)}) {
    REQUIRE((capUp.point(at) - cap.point(at)).norm() < 1e-12);
    REQUIRE((capUp.normal(cap.point(at)) - cap.normal(cap.point(at))).norm() < 1e-9);
  }
  const GeneratedBlocks sphere = generate("hex", pitch, h, theta, baseSurface("sphere", 0.6));
  const GeneratedBlocks meshed = generate("hex", pitch, h, theta, cap);
  for (std::size_t t = 0; t < sphere.meshes.size(); ++t) {
    REQUIRE(signedVolume(meshed.meshes[t]) == Approx(signedVolume(sphere.meshes[t])).epsilon(1e-3));
    for (std::size_t u = t + 1; u < meshed.meshes.size(); ++u)
      if ((polygonCentroid(meshed.tiling.tiles[t]) - polygonCentroid(meshed.tiling.tiles[u])).norm() < 2 * pitch)
        REQUIRE(sharedVolume(meshed.meshes[t], meshed.meshes[u], 10 * pitch) <= 1e-6 * pitch * pitch * h);
  }
  // Not a height field, too small, not a file.
  test::writeFile(dir / "closed.obj", "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                                      "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n");
  REQUIRE_THROWS_WITH(baseSurface(dir / "closed.obj", 0, 1.0), Catch::Contains("not a height field"));
  test::writeFile(dir / "small.obj", heightFieldObj(2, 0.01, [](double, double) { return 0.0; }));
  REQUIRE_THROWS_WITH(generate("hex", pitch, h, theta, baseSurface(dir / "small.obj", 0, 1.0)), Catch::Contains("beyond the surface"));
  REQUIRE_THROWS_WITH(baseSurface(dir / "missing.obj", 0, 1.0), Catch::Contains("mesh file of the surface"));
}

TEST_CASE("a tiling file's angle_<degrees> lines give those edges their own face angle, and bad ones are refused naming the group") {
  test::TempDir dir;
  // 4 x 4 squares of 10 mm; the edges along y (x = const) drawn again as lines in group angle_10.
  const int n = 4;
  const auto vertex = [&](int i, int j) { return 1 + i * (n + 1) + j; };
  const auto write = [&](const std::string& name, const std::string& lines, bool yUp = false) {
    std::ofstream obj(dir / name);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        obj << "v " << 10 * i - 20 << (yUp ? " 0 " + std::to_string(20 - 10 * j) : " " + std::to_string(10 * j - 20) + " 0") << "\n";
    obj << "o tiles\n";
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) obj << "f " << vertex(i, j) << " " << vertex(i + 1, j) << " " << vertex(i + 1, j + 1) << " " << vertex(i, j + 1) << "\n";
    obj << lines;
    return dir / name;
  };
  std::string angled = "g angle_10\n";
  for (int i = 1; i < n; ++i)
    for (int j = 0; j < n; ++j) angled += "l " + std::to_string(vertex(i, j)) + " " + std::to_string(vertex(i, j + 1)) + "\n";
  // Half the lines after a usemtl (assimp then names their mesh after the material: the group is
  // the node's name), a line of another group ignored.
  const std::size_t half = angled.find("l ", angled.size() / 2);
  const std::string withMaterial = angled.substr(0, half) + "usemtl red\n" + angled.substr(half) + "g notes\nl 1 7\n";
  const PlaneTiling tiling = readTilingFile(write("angled.obj", withMaterial), 1e-3);
  const PlaneTiling yUp = readTilingFile(write("angled_yup.obj", withMaterial, true), 1e-3, "y");
  const auto across = edgeNeighbours(tiling, 1e-9);
  const double angle = 5 * M_PI / 180, h = 0.00318;
  int given = 0;
  REQUIRE(yUp.edgeAngles.size() == tiling.edgeAngles.size());
  for (std::size_t t = 0; t < tiling.tiles.size(); ++t) {
    for (std::size_t k = 0; k < tiling.tiles[t].size(); ++k) {
      REQUIRE((yUp.tiles[t][k] - tiling.tiles[t][k]).norm() < 1e-12);
      REQUIRE(tileEdgeAngles(yUp, t, angle)[k] == tileEdgeAngles(tiling, t, angle)[k]);
    }
    const std::vector<double> angles = tileEdgeAngles(tiling, t, angle);
    for (std::size_t k = 0; k < angles.size(); ++k) {
      const auto& p = tiling.tiles[t];
      const bool alongY = std::abs(p[k].x() - p[(k + 1) % p.size()].x()) < 1e-12;
      const bool inner = std::abs(p[k].x()) < 0.015;  // not on the tiling's boundary x = +-20 mm
      INFO("tile " << t << " edge " << k);
      REQUIRE(angles[k] == Approx(alongY && inner ? 10 * M_PI / 180 : angle).epsilon(1e-12));
      given += alongY && inner ? 1 : 0;
    }
  }
  REQUIRE(given == 2 * 3 * n);  // each of the 12 lines on both its tiles

  // The blocks: no overlap, and each shared edge's plane, at that edge's angle, carries a face of both.
  const auto tilts = interlockingTilts(tiling, across, angle);
  const auto cuts = cornerCuts(tiling, across, tilts, h, angle);
  std::vector<TriangleMesh> meshes;
  for (std::size_t t = 0; t < tiling.tiles.size(); ++t) meshes.push_back(tiltedBlock(tiling.tiles[t], tilts[t], cuts[t], h, tileEdgeAngles(tiling, t, angle)));
  for (std::size_t t = 0; t < meshes.size(); ++t) {
    TriangleMesh copy = meshes[t];
    REQUIRE_FALSE(validateSolidMesh(copy, tiling.names[t]).reoriented);
    for (std::size_t u = t + 1; u < meshes.size(); ++u) REQUIRE(sharedVolume(meshes[t], meshes[u], 0.1) <= 1e-9 * 0.01 * 0.01 * h);
    const std::vector<double> angles = tileEdgeAngles(tiling, t, angle);
    for (std::size_t k = 0; k < across[t].size(); ++k) {
      const EdgeNeighbour& e = across[t][k];
      if (e.tile < 0) continue;
      const auto& p = tiling.tiles[t];
      const Eigen::Vector2d d = (p[(k + 1) % p.size()] - p[k]).normalized(), m(d.y(), -d.x());
      const Eigen::Vector3d normal(m.x() * std::cos(angles[k]), m.y() * std::cos(angles[k]), -tilts[t][k] * std::sin(angles[k]));
      const double offset = m.dot(p[k]) * std::cos(angles[k]);
      for (const TriangleMesh* mesh : {&meshes[t], &meshes[e.tile]})
        REQUIRE(std::count_if(mesh->vertices.begin(), mesh->vertices.end(),
                              [&](const Eigen::Vector3d& x) { return std::abs(normal.dot(x) - offset) <= 1e-12; }) >= 3);
    }
  }

  // Tiles with the same signs and angles, edge by edge, give the same block, vertex for vertex, up
  // to a translation (so that they share one shape: the canonical start keys the angles too).
  int alike = 0;
  for (std::size_t t = 0; t < meshes.size(); ++t)
    for (std::size_t u = t + 1; u < meshes.size(); ++u) {
      if (tilts[t] != tilts[u] || tileEdgeAngles(tiling, t, angle) != tileEdgeAngles(tiling, u, angle) || !cuts[t].empty() || !cuts[u].empty())
        continue;
      const Eigen::Vector3d shift = meshes[u].vertices[0] - meshes[t].vertices[0];
      REQUIRE(meshes[t].vertices.size() == meshes[u].vertices.size());
      for (std::size_t i = 0; i < meshes[t].vertices.size(); ++i) REQUIRE((meshes[t].vertices[i] + shift - meshes[u].vertices[i]).norm() < 1e-12);
      ++alike;
    }
  REQUIRE(alike > 0);

  const auto refused = [&](const std::string& name, const std::string& lines, const std::string& words) {
    INFO(name);
    REQUIRE_THROWS_WITH(readTilingFile(write(name, lines), 1e-3), Catch::Contains(words));
  };
  refused("word.obj", "g angle_steep\nl 6 7\n", "group 'angle_steep' names no angle");
  refused("steep.obj", "g angle_90\nl 6 7\n", "group 'angle_90': give the faces' tilt in degrees, in [0, 90)");
  refused("diagonal.obj", "g angle_10\nl 1 7\n", "the line (-20.000000, -20.000000)-(-10.000000, -10.000000) of group 'angle_10' is no tile's edge");
  refused("twice.obj", "g angle_10\nl 6 7\ng angle_7.5\nl 7 6\n", "is in groups 'angle_10' and 'angle_7.5'; give each edge one angle");
}

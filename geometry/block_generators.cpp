#include "geometry/block_generators.h"

#include "io/input_error.h"

#include <array>
#include <cmath>
#include <functional>
#include <string>

namespace tessera {

namespace {

// A block whose horizontal cross-section at each of the given levels is the rectangle
// |x| <= halfX(z), |y| <= halfY(z), joined by flat quads between consecutive levels.
// Level k's corners are 4k + c with c's bit 0 = x side, bit 1 = y side (0 = negative).
TriangleMesh stackedRectangles(int levels, double h, const std::function<double(double)>& halfX,
                               const std::function<double(double)>& halfY) {
  TriangleMesh mesh;
  for (int k = 0; k <= levels; ++k) {
    const double z = -0.5 * h + h * k / levels;
    for (int c = 0; c < 4; ++c)
      mesh.vertices.emplace_back((c & 1 ? 1 : -1) * halfX(z), (c & 2 ? 1 : -1) * halfY(z), z);
  }
  const auto quad = [&](int a, int b, int c, int d) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  };
  const int top = 4 * levels;
  quad(0, 2, 3, 1);                            // bottom, facing -z
  quad(top, top + 1, top + 3, top + 2);        // top, facing +z
  for (int k = 0; k < levels; ++k) {
    const int lo = 4 * k, hi = 4 * (k + 1);
    quad(lo + 0, lo + 1, hi + 1, hi + 0);      // y-
    quad(lo + 2, hi + 2, hi + 3, lo + 3);      // y+
    quad(lo + 0, hi + 0, hi + 2, lo + 2);      // x-
    quad(lo + 1, lo + 3, hi + 3, hi + 1);      // x+
  }
  return mesh;
}

void require(bool condition, const std::string& message) {
  if (!condition) throw InputError(message);
}

}  // namespace

TriangleMesh makeBox(double a, double b, double h) {
  require(a > 0 && b > 0 && h > 0, "box: sides must be positive");
  return stackedRectangles(1, h, [&](double) { return 0.5 * a; }, [&](double) { return 0.5 * b; });
}

TriangleMesh makePlanarBlock(double a, double h, double theta) {
  require(a > 0 && h > 0, "planar block: side and thickness must be positive");
  const double slope = std::tan(theta);
  require(std::abs(theta) < M_PI / 2 && h * std::abs(slope) < a,
          "planar block: the inclined faces meet inside the block (need thickness x tan(angle) < side)");
  return stackedRectangles(1, h, [&](double z) { return 0.5 * a + z * slope; },
                           [&](double z) { return 0.5 * a - z * slope; });
}

TriangleMesh makeWaveBlock(double a, double h, double theta, double amplitude, int waves, int levels) {
  require(a > 0 && h > 0, "wave block: side and thickness must be positive");
  require(waves >= 1, "wave block: --waves must be at least 1");
  require(levels >= 2 * waves + 1, "wave block: --levels must be at least 2 x waves + 1 to resolve the waves");
  require(waves <= 1000 && levels <= 10000,
          "wave block: at most 1000 --waves and 10000 --levels (finer than any grid can resolve)");
  require(std::abs(theta) < M_PI / 2, "wave block: the angle must be below 90 degrees");
  const double slope = std::tan(theta);
  const auto f = [&](double z) { return z * slope + amplitude * std::sin(2 * M_PI * waves * z / h); };
  for (int k = 0; k <= levels; ++k)
    require(std::abs(f(-0.5 * h + h * k / levels)) < 0.5 * a,
            "wave block: angle and amplitude make the faces cross (need |z tan(angle) + A sin(...)| < side / 2)");
  return stackedRectangles(levels, h, [&](double z) { return 0.5 * a + f(z); }, [&](double z) { return 0.5 * a - f(z); });
}

TriangleMesh makeOsteomorphicBlock(double a, double b, double h, double amplitude, double amplitudeY,
                                   int halfWaveSegments) {
  require(a > 0 && b > 0 && h > 0, "osteomorphic block: sides and thickness must be positive");
  require(std::abs(amplitude) < 0.5 * a && std::abs(amplitudeY) < 0.5 * b,
          "osteomorphic block: each amplitude must be below half the side it bends");
  // At a vertical corner edge the x- and y-faces meet at slopes c_x = 2 pi A_x / b and
  // c_y = 2 pi A_y / a; the faces cross there unless c_x c_y < 1.
  require(4 * M_PI * M_PI * std::abs(amplitude * amplitudeY) < a * b,
          "osteomorphic block: the x- and y-faces cross at the corners (need 4 pi^2 |A A_y| < a b)");
  require(halfWaveSegments >= 2 && halfWaveSegments <= 1000, "osteomorphic block: --levels must be from 2 to 1000");
  const int m = halfWaveSegments;
  const std::array<int, 3> n{amplitudeY != 0 ? 2 * m : 1, 2 * m, m};  // segments along x, y, z
  const std::array<double, 3> side{a, b, h};
  // The box's surface grid points, each made once, displaced off the x- and y-faces' interiors
  // only (exactly 0 on their edges: the z-faces and the corner edges stay flat and straight).
  std::vector<int> vertexAt(static_cast<std::size_t>(n[0] + 1) * (n[1] + 1) * (n[2] + 1), -1);
  TriangleMesh mesh;
  const auto vertex = [&](const std::array<int, 3>& g) {
    int& v = vertexAt[(static_cast<std::size_t>(g[0]) * (n[1] + 1) + g[1]) * (n[2] + 1) + g[2]];
    if (v >= 0) return v;
    Eigen::Vector3d p;
    std::array<bool, 3> boundary{};
    for (int d = 0; d < 3; ++d) {
      p[d] = -0.5 * side[d] + side[d] * g[d] / n[d];
      boundary[d] = g[d] == 0 || g[d] == n[d];
    }
    if (boundary[0] && !boundary[1] && !boundary[2])
      p.x() += amplitude * std::sin(2 * M_PI * p.y() / b) * std::cos(M_PI * p.z() / h);
    if (boundary[1] && !boundary[0] && !boundary[2])
      p.y() += amplitudeY * std::sin(2 * M_PI * p.x() / a) * std::cos(M_PI * p.z() / h);
    v = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(p);
    return v;
  };
  // Each face as quads over its two in-plane axes u, w (cyclic after the normal's axis, so that
  // e_u x e_w is the outward normal of the + face). A flat quad is split on a diagonal, the same on
  // both faces of a pair (one is the other moved by the side). A curved quad is a fan of four
  // triangles about a vertex on the surface over its middle: a diagonal would break the block's
  // mirror and rotational symmetries (each maps the diagonal onto the other one), and its nodes
  // would lose them too.
  const auto curved = [&](int axis) { return (axis == 0 && amplitude != 0) || (axis == 1 && amplitudeY != 0); };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int s = 0; s < 2; ++s)
      for (int i = 0; i < n[u]; ++i)
        for (int j = 0; j < n[w]; ++j) {
          const auto at = [&](int di, int dj) {
            std::array<int, 3> g{};
            g[axis] = s * n[axis];
            g[u] = i + di;
            g[w] = j + dj;
            return vertex(g);
          };
          const int p = at(0, 0), q = at(1, 0), r = at(1, 1), t = at(0, 1);
          if (curved(axis)) {
            Eigen::Vector3d middle;
            middle[axis] = (s - 0.5) * side[axis];
            middle[u] = side[u] * ((i + 0.5) / n[u] - 0.5);
            middle[w] = side[w] * ((j + 0.5) / n[w] - 0.5);
            if (axis == 0) middle.x() += amplitude * std::sin(2 * M_PI * middle.y() / b) * std::cos(M_PI * middle.z() / h);
            else middle.y() += amplitudeY * std::sin(2 * M_PI * middle.x() / a) * std::cos(M_PI * middle.z() / h);
            const int c = static_cast<int>(mesh.vertices.size());
            mesh.vertices.push_back(middle);
            const std::array<int, 4> ring = s == 1 ? std::array<int, 4>{p, q, r, t} : std::array<int, 4>{p, t, r, q};
            for (int k = 0; k < 4; ++k) mesh.triangles.push_back({ring[k], ring[(k + 1) % 4], c});
          } else if (s == 1) {
            mesh.triangles.push_back({p, q, r});
            mesh.triangles.push_back({p, r, t});
          } else {
            mesh.triangles.push_back({p, t, r});
            mesh.triangles.push_back({p, r, q});
          }
        }
  }
  return mesh;
}

TriangleMesh makeHexBlock(double r, double h, double theta) {
  require(r > 0 && h > 0, "hex block: inradius and thickness must be positive");
  const double slope = std::tan(theta);
  require(std::abs(theta) < M_PI / 2 && h * std::abs(slope) < r,
          "hex block: the inclined faces meet inside the block (need thickness x tan(angle) < inradius)");
  // Corner k joins faces k and k+1: solve n_k . p = d_k, n_{k+1} . p = d_{k+1} in the plane.
  const auto corner = [&](int k, double z) {
    const double a0 = M_PI / 3 * k, a1 = M_PI / 3 * (k + 1);
    const double d0 = r + (k % 2 == 0 ? 1 : -1) * z * slope, d1 = r + ((k + 1) % 2 == 0 ? 1 : -1) * z * slope;
    const double det = std::cos(a0) * std::sin(a1) - std::sin(a0) * std::cos(a1);
    return Eigen::Vector3d((d0 * std::sin(a1) - d1 * std::sin(a0)) / det, (std::cos(a0) * d1 - std::cos(a1) * d0) / det, z);
  };
  TriangleMesh mesh;
  for (double z : {-0.5 * h, 0.5 * h})
    for (int k = 0; k < 6; ++k) mesh.vertices.push_back(corner(k, z));
  for (int k = 1; k < 5; ++k) {
    mesh.triangles.push_back({0, k + 1, k});      // bottom, facing -z
    mesh.triangles.push_back({6, 6 + k, 6 + k + 1});  // top, facing +z
  }
  for (int k = 0; k < 6; ++k) {  // face k + 1 lies between corners k and k + 1
    const int a = k, b = (k + 1) % 6;
    mesh.triangles.push_back({a, b, 6 + b});
    mesh.triangles.push_back({a, 6 + b, 6 + a});
  }
  return mesh;
}

}  // namespace tessera

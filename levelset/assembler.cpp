#include "levelset/assembler.h"

#include "geometry/plane_tiling.h"

#include "io/input_error.h"
#include "geometry/length_unit.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_pieces.h"
#include "levelset/assembly.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fnmatch.h>
#include <limits>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// Reads one file into its pieces, turned z-up.
std::vector<AssemblyPart> readPieces(const std::string& file, const AssembleOptions& options, bool fixed) {
  MeshImportOptions import;
  import.metresPerUnit = parseLengthUnit(options.unit).metres;
  import.up = options.up;
  ImportedMesh imported = importMesh(file, import);
  std::vector<TriangleMesh> meshes = splitPieces(imported.mesh);
  std::vector<AssemblyPart> pieces;
  const std::string stem = shapeNameFromPath(file);
  const int digits = static_cast<int>(std::to_string(meshes.size()).size());
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    AssemblyPart p;
    if (meshes.size() == 1) p.name = stem;
    else {
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_%0*zu", digits, k + 1);
      p.name = stem.substr(0, 64 - std::strlen(suffix)) + suffix;
    }
    p.label = meshes.size() == 1 ? file : file + " (piece " + std::to_string(k + 1) + " of " + std::to_string(meshes.size()) + ")";
    p.mesh = std::move(meshes[k]);
    p.fixed = fixed;
    pieces.push_back(std::move(p));
  }
  return pieces;
}

// If `b` is `a` moved rigidly (same triangles, vertices in the same order), the placement of a's
// source mesh that gives b: x_b = R x_a + t (Kabsch: Arun, Huang & Blostein, IEEE PAMI 9, 1987).
std::optional<Placement> rigidMatch(const TriangleMesh& a, const TriangleMesh& b, double tolerance) {
  if (a.vertices.size() != b.vertices.size() || a.triangles != b.triangles) return std::nullopt;
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    ca += a.vertices[i];
    cb += b.vertices[i];
  }
  ca /= static_cast<double>(a.vertices.size());
  cb /= static_cast<double>(b.vertices.size());
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < a.vertices.size(); ++i) h += (a.vertices[i] - ca) * (b.vertices[i] - cb).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;  // a rotation, not a mirror
  const Eigen::Matrix3d r = svd.matrixV() * d * svd.matrixU().transpose();
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    if ((r * (a.vertices[i] - ca) + cb - b.vertices[i]).norm() > tolerance) return std::nullopt;
  Placement p;
  p.rotation = Eigen::Quaterniond(r).normalized();
  p.translation = cb - r * ca;
  return p;
}

double distanceToSegment(const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - x).norm();
}

// Distance from each centroid to its nearest neighbour's, in plan.
std::vector<double> nearestNeighbour(const std::vector<Eigen::Vector2d>& centres) {
  const std::size_t n = centres.size();
  std::vector<double> d(n, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (i != j) d[i] = std::min(d[i], (centres[i] - centres[j]).norm());
  return d;
}

std::vector<Eigen::Vector2d> planCentres(const Bundle& bundle) {
  std::vector<Eigen::Vector2d> centres;
  for (const Body& b : bundle.bodies) centres.push_back(b.position.head<2>());
  return centres;
}

// The outer ring of bodies with these plan centroids (outerRingBodies).
std::vector<int> outerRing(const std::vector<Eigen::Vector2d>& centres) {
  const std::vector<Eigen::Vector2d> hull = convexHull(centres);
  const std::vector<double> spacing = nearestNeighbour(centres);
  std::vector<int> ring;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < hull.size(); ++k) d = std::min(d, distanceToSegment(centres[i], hull[k], hull[(k + 1) % hull.size()]));
    if (hull.size() < 3 || d < 0.5 * spacing[i]) ring.push_back(static_cast<int>(i));
  }
  return ring;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// The number a body's name ends in (Part_043 and part43 are 43), or -1 when it ends in none.
long nameNumber(const std::string& name) {
  const std::size_t start = name.find_last_not_of("0123456789") + 1;  // npos + 1 = 0: all digits
  if (start >= name.size() || name.size() - start > 15) return -1;
  return std::stol(name.substr(start));
}

}  // namespace

std::vector<int> outerRingBodies(const Bundle& bundle) { return outerRing(planCentres(bundle)); }

void estimateSpan(const Bundle& bundle, double& length, int& interfaces, std::string& rule) {
  const double pitch = median(nearestNeighbour(planCentres(bundle)));
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Body& b : bundle.bodies)
    if (!b.fixed) {
      lo = lo.cwiseMin(b.position.head<2>());
      hi = hi.cwiseMax(b.position.head<2>());
    }
  length = (hi - lo).minCoeff() + pitch;
  interfaces = static_cast<int>(std::lround(length / pitch)) + 1;
  char text[200];
  std::snprintf(text, sizeof text,
                "estimated: free centroids span %.4g mm across the shorter side, + the median pitch %.4g mm = L; "
                "M = L / pitch + 1",
                (hi - lo).minCoeff() * 1e3, pitch * 1e3);
  rule = text;
}

Bundle assembleParts(const std::vector<std::string>& files, const AssembleOptions& options, PrepLog& log,
                     AssembleReport& report) {
  if (options.unit.empty()) throw InputError("state the files' length unit with --unit (mm, cm, m, in): mesh files carry none");
  std::vector<AssemblyPart> pieces;
  for (const std::string& frame : options.frameFiles) {
    if (!fs::exists(frame)) throw InputError(frame + ": no such frame file; give the mesh of the fixed frame with --frame");
    for (AssemblyPart& p : readPieces(frame, options, true)) pieces.push_back(std::move(p));
  }
  for (const std::string& file : files)
    for (AssemblyPart& p : readPieces(file, options, false)) pieces.push_back(std::move(p));
  report.files = files.size() + options.frameFiles.size();
  report.pieces = pieces.size();
  if (pieces.empty()) throw InputError("no part files given: list the part meshes (or a folder of them)");
  return assembleParts(std::move(pieces), options, log, report);
}

Bundle assembleParts(std::vector<AssemblyPart> pieces, const AssembleOptions& options, PrepLog& log, AssembleReport& report) {

  // Names and supports first: what can be refused is refused before any shape is built.
  std::vector<Eigen::Vector2d> centres;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (pieces[j].name == pieces[i].name)
        throw InputError(pieces[i].label + ": a second body named '" + pieces[i].name + "'; rename one of the files");
    for (const std::string& pattern : options.fixPatterns)
      if (fnmatch(pattern.c_str(), pieces[i].name.c_str(), 0) == 0) pieces[i].fixed = true;
    centres.push_back(computeMassProperties(pieces[i].mesh).centroid.head<2>());
  }
  for (long id : options.fixIds) {
    bool found = false;
    for (AssemblyPart& piece : pieces)
      if (nameNumber(piece.name) == id) piece.fixed = found = true;
    if (!found)
      throw InputError("--fix-ids: no part's name ends in " + std::to_string(id) +
                       " (the ids are the numbers at the end of the part files' names, e.g. Part_43.obj is 43)");
  }
  if (options.fixOuterRing)
    for (int i : outerRing(centres)) pieces[i].fixed = true;
  const auto fixedCount = std::count_if(pieces.begin(), pieces.end(), [](const AssemblyPart& p) { return p.fixed; });
  if (fixedCount == 0)
    throw InputError("no body is fixed: name the supports with --fix PATTERN or --fix-ids LIST, give the frame mesh "
                     "with --frame FILE, or use --fix-outer-ring");
  if (fixedCount == static_cast<long>(pieces.size()))
    throw InputError("every body is fixed (" + std::to_string(fixedCount) + "): nothing can move; check --fix patterns");

  Bundle bundle;
  bundle.generator = generatorVersion();
  bundle.sourceUp = options.up;
  std::vector<int> firstPiece;  // per shape: the piece whose mesh is its source
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const AssemblyPart& piece = pieces[i];
    const double size = boundingBox(piece.mesh.vertices).diagonal().norm();
    std::optional<Placement> placement;
    int shape = -1;
    for (std::size_t s = 0; s < firstPiece.size() && !placement; ++s)
      if ((placement = rigidMatch(pieces[firstPiece[s]].mesh, piece.mesh, options.sameShapeTolerance * size)))
        shape = static_cast<int>(s);
    if (!placement) {
      const ShapeSource source{piece.label, options.unit, parseLengthUnit(options.unit).metres};
      bundle.shapes.push_back(buildShape(piece.name, piece.mesh, source, options.resolution, piece.label, log, options.limits));
      firstPiece.push_back(static_cast<int>(i));
      shape = static_cast<int>(bundle.shapes.size()) - 1;
      placement = Placement{};  // the shape's source mesh is this piece, in place
    }
    placement->name = piece.name;
    placement->fixed = piece.fixed;
    bundle.bodies.push_back(placeBody(bundle.shapes[shape], shape, *placement));
  }

  if (options.spanLength > 0 && options.spanInterfaces > 0) {
    bundle.spanLength = options.spanLength;
    bundle.spanInterfaces = options.spanInterfaces;
    report.spanRule = "given";
  } else {
    estimateSpan(bundle, bundle.spanLength, bundle.spanInterfaces, report.spanRule);
    if (options.spanLength > 0) {  // L given: M from it, at the estimated pitch
      const double pitch = median(nearestNeighbour(planCentres(bundle)));
      bundle.spanInterfaces = static_cast<int>(std::lround(options.spanLength / pitch)) + 1;
      bundle.spanLength = options.spanLength;
      report.spanRule = "L given; M = L / pitch + 1 at the median pitch";
    }
    if (options.spanInterfaces > 0) {
      bundle.spanInterfaces = options.spanInterfaces;
      report.spanRule = "M given; " + report.spanRule;
    }
  }
  return bundle;
}

}  // namespace tessera

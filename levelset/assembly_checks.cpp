#include "levelset/assembly_checks.h"

#include "io/input_error.h"
#include "geometry/length_unit.h"
#include "io/output_directory.h"

#include <filesystem>

#include <algorithm>

namespace tessera {

void checkBundleOutput(const std::string& directory, bool replace) {
  namespace fs = std::filesystem;
  if (fs::exists(directory) && !fs::is_directory(directory))
    throw InputError(directory + ": exists and is not a directory; give a bundle directory with -o");
  if (fs::exists(fs::path(directory) / kBundleFileName) && !replace)
    throw InputError(directory + ": holds a bundle already; choose another -o or pass --replace");
  requireWritableDirectory(directory);
}

double finestVoxel(const Bundle& bundle) {
  double finest = 1e300;
  for (const Shape& s : bundle.shapes) finest = std::min(finest, s.sdf.voxelSize);
  return finest;
}

void refuseOverlaps(const Bundle& bundle, const AssemblyCheck& check, double tolerance, const std::string& where,
                    const std::string& fix) {
  if (check.overlaps.empty()) return;
  const BodyPair& worst = check.overlaps.front();
  throw InputError(where + "bodies '" + bundle.bodies[worst.a].name + "' and '" + bundle.bodies[worst.b].name +
                   "' overlap by " + formatMillimetres(-worst.separation) + " (tolerance " + formatMillimetres(tolerance) + "; " +
                   std::to_string(check.overlaps.size()) + " overlapping pair(s) in all); " + fix);
}

namespace {

// Positions and a span no arrangement of these blocks can have: a body farther from the middle of
// the others than all of them side by side, or a span longer than the whole assembly (a layout's
// 1e300 mm was accepted and made a bundle).
void refuseBeyondReach(const Bundle& bundle) {
  double block = 0;
  for (const Shape& s : bundle.shapes) block = std::max(block, boundingBox(s.mesh.vertices).diagonal().norm());
  const double reach = static_cast<double>(bundle.bodies.size()) * block;
  Eigen::Vector3d middle;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> x;
    for (const Body& b : bundle.bodies) x.push_back(b.position[k]);
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    middle[k] = x[x.size() / 2];
  }
  Eigen::AlignedBox3d extent;
  for (const Body& b : bundle.bodies) {
    const double away = (b.position - middle).stableNorm();
    if (!(away <= reach))
      throw InputError("body '" + b.name + "' lies " + formatMillimetres(away) + " from the middle of the assembly, farther than all " +
                       std::to_string(bundle.bodies.size()) + " blocks side by side (" + formatMillimetres(reach) +
                       "); check its position and the layout's unit");
    extent.extend(b.position);
  }
  const double across = extent.diagonal().norm() + block;
  if (bundle.spanLength > across)
    throw InputError("the span length " + formatMillimetres(bundle.spanLength) + " is longer than the whole assembly (" +
                     formatMillimetres(across) + " across); give the free span L in the layout's unit");
}

}  // namespace

AssemblySummary checkAssemblyBeforeWriting(const Bundle& bundle, std::optional<double> overlapTolerance, double gap,
                                           const std::string& overlapFix, const std::string& apartFix, bool refuseApart) {
  const double voxel = finestVoxel(bundle);
  const double tolerance = overlapTolerance ? *overlapTolerance : 0.1 * voxel;
  const double touch = gap + 0.5 * voxel;
  AssemblySummary summary;
  const AssemblyLevelSets levelSets(bundle);
  summary.check = checkAssembly(bundle, levelSets, tolerance, touch);
  refuseOverlaps(bundle, summary.check, tolerance, "", overlapFix);
  if (bundle.bodies.size() > 1 && summary.check.contacts.empty()) {
    const std::string apart = "no two of the " + std::to_string(bundle.bodies.size()) + " bodies touch (nothing within " +
                              formatMillimetres(touch) + " of another): the blocks lie apart; " + apartFix;
    if (refuseApart) throw InputError(apart);
    summary.warnings.push_back(apart);
  }
  refuseBeyondReach(bundle);
  for (int i : summary.check.isolated)
    summary.warnings.push_back("body '" + bundle.bodies[i].name + "' touches no other body (nothing within " +
                               formatMillimetres(touch) + ")");
  const double threshold = 0.01 * 0.5 * voxel;
  for (const VerticalLock& l : verticalLocks(bundle, levelSets, 0.5 * voxel)) {
    ++summary.free;
    if (l.upDepth > threshold && l.downDepth > threshold) ++summary.locked;
    else
      summary.notes.push_back("free body '" + bundle.bodies[l.body].name + "' is not held " +
                              (l.upDepth > threshold ? "downward" : l.downDepth > threshold ? "upward" : "up or down") +
                              " by its neighbours");
  }
  if (summary.free > 0 && summary.locked == 0)
    summary.warnings.push_back("no free body is held both up and down by its neighbours: the slab does not interlock");
  return summary;
}

}  // namespace tessera

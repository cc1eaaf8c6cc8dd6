#include "run/presets.h"

#include "io/input_error.h"
#include "run/scene.h"

namespace tessera {

// Measured on the default test by bench/convergence.sh against the finest affordable reference
// (0.15 mm nodes, 30 mm/s, factor 0.5); numbers in docs/performance.md, "Accuracy". Node spacing
// dominates the error (and P_max converges non-monotonically); speed 6-120 mm/s and factor
// 0.25-1 change results by < 0.7 %. Both are ratios (docs/scene.md, "Scale"): node spacing of each
// shape's thinnest extent, speed of c h / L; the millimetres quoted are those of the paper's slab.
namespace {

std::vector<std::pair<std::string, double>> keys(double spacingMillimetresOnPaperBlock, double speedTimesPaper) {
  return {{"resolution.node_spacing", 0.0},
          {"resolution.node_spacing_ratio", spacingMillimetresOnPaperBlock * 1e-3 / kPaperThickness},
          {"indenter.speed", 0.0},
          {"indenter.speed_ratio", speedTimesPaper * kPaperSpeedRatio},
          {"solver.time_step_factor", 0.5}};
}

}  // namespace

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"fast", "nodes t/2.65, 20x the paper's speed (1.2 mm, 120 mm/s on its slab): P_max -3 %, K +12 %, W -2 %; 4-7 s on one thread",
       keys(1.2, 20)},
      {"default", "nodes t/5.3, 5x the paper's speed (0.6 mm, 30 mm/s on its slab): P_max +8 %, K +5 %, W +2 %; 33 s on one thread",
       keys(0.6, 5)},
      {"paper", "nodes t/5.3 at the paper's speed (0.6 mm, 6 mm/s): as default (speed changes < 0.1 %); 100 s on two threads",
       keys(0.6, 1)},
      {"fine", "nodes t/10.6, 5x the paper's speed (0.3 mm, 30 mm/s): P_max +6 %, K +2 %, W +4 %; 65 s on one thread",
       keys(0.3, 5)},
  };
  return all;
}

const Preset& findPreset(const std::string& name) {
  std::string names;
  for (const Preset& p : presets()) {
    if (p.name == name) return p;
    names += (names.empty() ? "" : ", ") + p.name;
  }
  throw InputError("unknown preset '" + name + "'; choose one of " + names);
}

}  // namespace tessera

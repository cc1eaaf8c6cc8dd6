#include "run/presets.h"

#include "io/input_error.h"
#include "run/scene.h"

namespace tessera {

// Measured on the default test by bench/convergence.sh against the finest affordable reference
// (0.15 mm uniform nodes, 30 mm/s, factor 0.5); numbers in docs/performance.md, "Accuracy". Node
// spacing dominates the error, and nodes graded to a quarter of the spacing at the sharp edges
// (where the blocks hinge) take most of it away; speed 6-120 mm/s and factor 0.25-1 change
// results by < 0.7 %. All are ratios (docs/scene.md, "Scale"): node spacing of each shape's
// thinnest extent, speed of c h / L; the millimetres quoted are those of the paper's slab.
namespace {

std::vector<std::pair<std::string, double>> keys(double spacingMillimetresOnPaperBlock, double edgeFraction,
                                                 double speedTimesPaper) {
  return {{"resolution.node_spacing", 0.0},
          {"resolution.node_spacing_ratio", spacingMillimetresOnPaperBlock * 1e-3 / kPaperThickness},
          {"resolution.edge_spacing_fraction", edgeFraction},
          {"resolution.size_gradient", 0.5},
          {"indenter.speed", 0.0},
          {"indenter.speed_ratio", speedTimesPaper * kPaperSpeedRatio},
          {"solver.time_step_factor", 0.5}};
}

}  // namespace

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"fast", "uniform nodes t/2.65, 20x the paper's speed (1.2 mm, 120 mm/s on its slab): P_max -1 %, K +9 %, W +8 %; 1 s on two threads",
       keys(1.2, 1.0, 20)},
      {"default", "nodes t/5.3 graded to t/21 at sharp edges, 5x the paper's speed (0.6 mm, 0.15 mm, 30 mm/s on its slab): "
       "P_max +3 %, K -1 %, W +3 %; 10 s on two threads",
       keys(0.6, 0.25, 5)},
      {"paper", "the paper's uniform nodes t/5.3 at its speed (0.6 mm, 6 mm/s): P_max +9 %, K -5 %, W +7 %; 24 s on two threads",
       keys(0.6, 1.0, 1)},
      {"fine", "nodes t/10.6 graded to t/42 at sharp edges, 5x the paper's speed (0.3 mm, 0.075 mm, 30 mm/s): "
       "P_max +0.7 %, K +0.9 %, W -0.7 %; 20 s on two threads",
       keys(0.3, 0.25, 5)},
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

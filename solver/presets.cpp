#include "solver/presets.h"

#include "geometry/input_error.h"

namespace tessera {

// Measured on the default test by bench/convergence.sh against the finest affordable reference
// (0.15 mm nodes, 30 mm/s, factor 0.5); numbers in docs/performance.md, "Accuracy". Node spacing
// dominates the error (and P_max converges non-monotonically); speed 6-120 mm/s and factor
// 0.25-1 change results by < 0.7 %. Node spacings are absolute: measured on the 10 mm default block.
const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"fast", "1.2 mm nodes, 120 mm/s: P_max -3 %, K +12 %, W -2 % against the reference; 4-7 s on one thread",
       {{"resolution.node_spacing", 1.2e-3}, {"indenter.speed", 0.12}, {"solver.time_step_factor", 0.5}}},
      {"default", "0.6 mm nodes (the paper's), 30 mm/s: P_max +8 %, K +5 %, W +2 %; 40 s on one thread",
       {{"resolution.node_spacing", 0.6e-3}, {"indenter.speed", 0.03}, {"solver.time_step_factor", 0.5}}},
      {"paper", "0.6 mm nodes, 6 mm/s, the paper's protocol: as default (speed changes < 0.1 %); 87 s on two threads",
       {{"resolution.node_spacing", 0.6e-3}, {"indenter.speed", 0.006}, {"solver.time_step_factor", 0.5}}},
      {"fine", "0.3 mm nodes, 30 mm/s: P_max +6 %, K +2 %, W +4 %; 130 s on one thread",
       {{"resolution.node_spacing", 0.3e-3}, {"indenter.speed", 0.03}, {"solver.time_step_factor", 0.5}}},
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

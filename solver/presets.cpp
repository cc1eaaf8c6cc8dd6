#include "solver/presets.h"

#include "geometry/input_error.h"

namespace tessera {

// Measured on the default test against the reference (0.3 mm nodes, 30 mm/s, factor 0.5: the
// "fine" preset) by bench/convergence.sh; numbers in docs/performance.md, "Accuracy". Node spacing
// dominates the error; speed and time-step factor within these ranges change results by < 0.6 %.
const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"fast", "0.6 mm nodes, 120 mm/s: P_max, K, W within 2.7 % of the reference, 11 s on one thread",
       {{"resolution.node_spacing", 0.6e-3}, {"indenter.speed", 0.12}, {"solver.time_step_factor", 0.5}}},
      {"default", "0.6 mm nodes, 30 mm/s (assets/scenes/default.toml): within 2.8 %, 40 s on one thread",
       {{"resolution.node_spacing", 0.6e-3}, {"indenter.speed", 0.03}, {"solver.time_step_factor", 0.5}}},
      {"paper", "0.6 mm nodes, 6 mm/s, the paper's protocol: within 2.8 %, 200 s on one thread, 107 s on two",
       {{"resolution.node_spacing", 0.6e-3}, {"indenter.speed", 0.006}, {"solver.time_step_factor", 0.5}}},
      {"fine", "0.3 mm nodes, 30 mm/s: the reference of the others, 130 s on one thread",
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

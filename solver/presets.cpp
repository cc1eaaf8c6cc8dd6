#include "solver/presets.h"

#include "geometry/input_error.h"

namespace tessera {

// Measured on the default test against the reference (0.3 mm nodes, 15 mm/s, factor 0.5) by
// bench/convergence.sh; numbers in docs/performance.md, "Accuracy".
const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"fast", "FAST_DESCRIPTION",
       {{"resolution.node_spacing", 1.2e-3}, {"indenter.speed", 0.12}, {"solver.time_step_factor", 1.0}}},
      {"default", "DEFAULT_DESCRIPTION",
       {{"resolution.node_spacing", 0.6e-3}, {"indenter.speed", 0.03}, {"solver.time_step_factor", 0.5}}},
      {"paper", "PAPER_DESCRIPTION",
       {{"resolution.node_spacing", 0.6e-3}, {"indenter.speed", 0.006}, {"solver.time_step_factor", 0.5}}},
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

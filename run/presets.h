#pragma once
#include <string>
#include <utility>
#include <vector>

namespace tessera {

/// A named speed/accuracy setting of a run (`tessera run --preset NAME`): scene keys and their
/// values, applied over the scene file. The error each gives on the default test, against the
/// finest affordable reference, is measured by bench/convergence.sh (docs/performance.md).
struct Preset {
  std::string name;
  std::string description;                                   ///< one line: what it is for, its measured error
  std::vector<std::pair<std::string, double>> overrides;     ///< "table.key" -> value (SI)
};

const std::vector<Preset>& presets();

/// The preset of this name; InputError listing the names otherwise.
const Preset& findPreset(const std::string& name);

}  // namespace tessera

#pragma once
#include "solver/contact_parameters.h"
#include "solver/solver_settings.h"

#include <string>
#include <utility>
#include <vector>

namespace tessera {

/// The indenter of the test (docs/scene.md).
struct IndenterSettings {
  double radius = 2.5e-3;   ///< m
  double speed = 6e-3;      ///< m/s, downward
  std::string target;       ///< body to load; empty: the free body nearest the slab's centre (x, y)
  double clearance = 1e-6;  ///< m, start this far above the target's top
  double stiffnessFactor = 1.0;  ///< its contact stiffnesses are this x the blocks' k_n and k_t
};

/// The loading protocol (docs/scene.md, docs/physics.md "Protocol"). Ratios are of h, the loaded
/// block's extent along the loading direction, or of each body's own size.
struct ProtocolSettings {
  double settleKinetic = 1e-12;   ///< J: settled when the kinetic energy is below this ...
  double settleMaxTime = 0.05;    ///< s: ... or after this much simulated time (with a warning)
  double deltaMax = 0.0;          ///< m: stop at this deflection (0: deltaMaxRatio x h)
  double deltaMaxRatio = 2.0;     ///< delta_max / h when deltaMax is 0 (the paper's snapshots reach 1.5 h)
  /// The failure deflection is where the load first falls below this fraction of P_max after the peak.
  double failureLoadFraction = 0.1;
  /// Stop before deltaMax once the load has stayed below 1 % of P_max over quietTravel x h and
  /// every free body is at rest (slower than restSpeedRatio x the indenter's speed) or fallen.
  bool stopOnFailure = true;
  double quietTravel = 0.1;
  double restSpeedRatio = 0.01;
  /// Fallen and retired bodies (FallenRule): a ratio of each body's size.
  double fallenClearance = 0.1;
};

struct OutputSettings {
  double sampleEvery = 10e-6;     ///< m of indenter travel between curve samples
  double snapshotEvery = 0.5e-3;  ///< m of indenter travel between body-pose snapshots
  double progressSeconds = 2.0;   ///< s of wall time between progress lines
  double checkpointSeconds = 30.0; ///< s of wall time between checkpoints (and result files)
};

/// Re-prepare the bundle's shapes at another resolution for this run (0: keep the bundle's).
struct ResolutionOverride {
  double nodeSpacing = 0.0;  ///< m
  double voxelSize = 0.0;    ///< m
};

/// Everything a `tessera run` needs besides the bundle itself. Lengths in m, SI throughout.
struct Scene {
  std::string path;              ///< the scene file
  std::string bundle;            ///< bundle directory (relative paths resolved against the scene's folder)
  ContactParameters contact;     ///< spanLength / spanInterfaces 0 = take them from the bundle
  SolverSettings solver;
  IndenterSettings indenter;
  ProtocolSettings protocol;
  OutputSettings output;
  ResolutionOverride resolution;
};

/// Reads a TOML scene file; unknown keys, wrong types and out-of-range values are InputErrors
/// naming the file, the key and the accepted range. See docs/scene.md.
Scene readScene(const std::string& path);

/// The text of a scene file with some numeric keys replaced ("table.key" -> value) and its bundle
/// path made absolute, for the cases of a sweep. Throws InputError for a key the scene format
/// does not have (the result is re-read with readScene, which checks ranges).
std::string sceneWithOverrides(const std::string& path, const std::vector<std::pair<std::string, double>>& overrides);

}  // namespace tessera

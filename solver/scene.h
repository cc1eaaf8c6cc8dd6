#pragma once
#include "solver/contact_parameters.h"
#include "solver/solver_settings.h"

#include <string>
#include <utility>
#include <vector>

namespace tessera {

/// The indenter of the test (DESIGN §5, §6).
struct IndenterSettings {
  double radius = 2.5e-3;   ///< m
  double speed = 6e-3;      ///< m/s, downward
  std::string target;       ///< body to load; empty: the free body nearest the slab's centre (x, y)
  double clearance = 1e-6;  ///< m, start this far above the target's top
};

/// The loading protocol (docs/scene.md).
struct ProtocolSettings {
  double settleKinetic = 1e-12;   ///< J: settled when the kinetic energy is below this ...
  double settleMaxTime = 0.05;    ///< s: ... or after this much simulated time (with a warning)
  double deltaMax = 6e-3;         ///< m: stop at this deflection
  bool stopOnFailure = true;      ///< stop once the load is gone for good and the loaded block has fallen
  double fallenDistance = 0.0;    ///< m: a body this far below its settled position has fallen
                                  ///< (0: the thickness of the loaded block)
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

#pragma once
#include "solver/contact_parameters.h"
#include "solver/solver_settings.h"

#include <Eigen/Core>

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tessera {

/// The indenter speed as a ratio of c (h / L)^2, c = sqrt(E / rho) the bar wave speed, h the loaded
/// block's thickness, L the span: a plate's fundamental frequency goes as c h / L^2, so a loading
/// over a travel of order h lasts the same number of periods of the slab, and keeps the same
/// quasi-static ratio KE / W, on any slab at any scale. kPaperSpeedRatio is the paper's 6 mm/s on
/// its slab (E = 4.2 GPa, rho = 2500 kg/m^3, h = 3.18 mm, L = 50 mm); the default is 5 x that
/// (30 mm/s there: KE / W < 1e-3; results within 0.1 % of 6 mm/s, docs/performance.md).
inline constexpr double kPaperSpan = 50e-3;  // m, L of the paper's 7 x 7 slab
inline const double kPaperSpeedRatio =
    6e-3 / (std::sqrt(4.2e9 / 2500.0) * (kPaperThickness / kPaperSpan) * (kPaperThickness / kPaperSpan));
inline const double kDefaultSpeedRatio = 5 * kPaperSpeedRatio;

/// The indenter of the test (docs/scene.md).
struct IndenterSettings {
  double radius = 0.0;                           ///< m; 0: radiusRatio x h
  double radiusRatio = 2.5e-3 / kPaperThickness; ///< radius / h when radius is 0 (2.5 mm on the paper's block)
  /// m/s, downward; 0: speedRatio x c (h / L)^2 (kPaperSpeedRatio; docs/physics.md, "Protocol").
  double speed = 0.0;
  double speedRatio = kDefaultSpeedRatio;
  std::string target;       ///< body to load; empty: the free body nearest the slab's centre (x, y)
  Eigen::Vector2d offset{0, 0};  ///< m, where to load in plan, from the target's centroid
  bool atPoint = false;          ///< load at `point` instead: the topmost free body under it
  Eigen::Vector2d point{0, 0};   ///< m, (x, y) on the slab's upper surface
  double clearance = 1e-6;  ///< m, start this far above the first contact with the target (its surface nodes)
  double stiffnessFactor = 1.0;  ///< its contact stiffnesses are this x the blocks' k_n and k_t
};

/// The loading protocol (docs/scene.md, docs/physics.md "Protocol"). Ratios are of h, the loaded
/// block's extent along the loading direction, or of each body's own size.
struct ProtocolSettings {
  /// J: settled when the kinetic energy is below this (0: settleKineticRatio x the free bodies'
  /// potential energy scale sum m_i |g| h_i) ...
  double settleKinetic = 0.0;
  double settleKineticRatio = 1e-9;
  /// s: ... or after this much simulated time (with a warning); 0: settleTimeLimit (indentation.h),
  /// 0.051 s on the paper's slab, 2.2 s for a 1.5 m shell of 60 mm parts.
  double settleMaxTime = 0.0;
  double settleMaxTimeRatio = 0.05 / (kPaperSpan * kPaperSpan / (std::sqrt(4.2e9 / 2500.0) * kPaperThickness));
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
  /// K is fitted over delta in [0, min(stiffnessFitRatio x h, delta at the peak / 2)] (0.4 mm on the paper's block).
  double stiffnessFitRatio = 0.4e-3 / kPaperThickness;
  /// Quasi-static check: the run warns and summary.json flags it when KE / W before the peak exceeds this.
  double quasiStaticLimit = 1e-2;
  /// > 0: adaptive loading rate. Up to the peak the indenter's speed is lowered (to 1/64 of the
  /// protocol's at most) where KE / W exceeds this, and raised back towards the protocol's speed
  /// where KE / W is below a quarter of it (run/loading_rate.h). 0: constant speed.
  double quasiStaticTarget = 0.0;
};

struct OutputSettings {
  double sampleEvery = 10e-6;     ///< m of indenter travel between curve samples
  double snapshotEvery = 0.5e-3;  ///< m of indenter travel between body-pose snapshots
  double progressSeconds = 2.0;   ///< s of wall time between progress lines
  double checkpointSeconds = 30.0; ///< s of wall time between checkpoints (and result files)
};

/// Re-prepare the bundle's shapes at another resolution for this run (0: keep the bundle's).
struct ResolutionOverride {
  double nodeSpacing = 0.0;       ///< m
  double voxelSize = 0.0;         ///< m
  double nodeSpacingRatio = 0.0;  ///< of each shape's thinnest extent (used when nodeSpacing is 0)
  double voxelRatio = 0.0;        ///< of each shape's thinnest extent (used when voxelSize is 0)
  double edgeSpacingFraction = 0.0;  ///< node spacing at sharp edges, of the node spacing
  double sizeGradient = 0.0;         ///< growth of the node spacing away from sharp edges
  bool any() const {
    return nodeSpacing > 0 || voxelSize > 0 || nodeSpacingRatio > 0 || voxelRatio > 0 || edgeSpacingFraction > 0 ||
           sizeGradient > 0;
  }
};

/// A slab generated from a tiling, in place of a bundle ([geometry], docs/scene.md): the recipe of
/// `tessera tile --tiling` in SI units (the angle in degrees). Defaults: the paper's slab.
struct GeometryRecipe {
  std::string tiling = "square";  ///< square, hex, triangle, rhombille, voronoi, or a polygon mesh file (m)
  double pitch = 10e-3;           ///< m, between the centres of tiles sharing an edge
  int columns = 7, rows = 7;      ///< grid = [columns, rows]
  double thickness = 3.18e-3;     ///< m
  double angle = 5;               ///< degrees, the faces' tilt
  std::string surface = "plane";  ///< plane, sphere, cylinder, or a surface mesh file (m)
  std::string up = "z";           ///< the tiling and surface files' up axis, turned into +z
  double radius = 0;              ///< m (sphere, cylinder)
  bool fixPerimeter = true;       ///< fix = "perimeter" (or "none")
  int seed = 1;                   ///< voronoi
  /// Or a block family of `tessera block` (planar, wave, box, osteomorphic) of side `size`, laid
  /// on the square grid `size` apart (turned in a checkerboard but for osteomorphic); "" = the tiling.
  std::string family;
  double size = 10e-3;            ///< m, the family block's side a
  double amplitude = 0;           ///< m, of curved faces (wave, osteomorphic); 0 = 0.02 size
};

/// Everything a `tessera run` needs besides the bundle itself. Lengths in m, SI throughout.
struct Scene {
  std::string path;              ///< the scene file
  std::string bundle;            ///< bundle directory (relative paths resolved against the scene's folder)
  std::optional<GeometryRecipe> geometry;  ///< or: the slab to generate (then `bundle` is set when it is built)
  ContactParameters contact;     ///< spanLength / spanInterfaces 0 = take them from the bundle
  SolverSettings solver;
  IndenterSettings indenter;
  ProtocolSettings protocol;
  OutputSettings output;
  ResolutionOverride resolution;
};

/// The text of a scene file; InputError naming it when it is not a file.
std::string readSceneFile(const std::string& path);
/// Reads a TOML scene file; unknown keys, wrong types and out-of-range values are InputErrors
/// naming the file, the key and the accepted range. See docs/scene.md.
Scene readScene(const std::string& path);
/// A scene from its text; `path` names it in messages and anchors a relative bundle path.
Scene readSceneText(const std::string& text, const std::string& path);

/// The text of a scene file with some numeric keys replaced ("table.key" -> value) and its bundle
/// path made absolute, for the cases of a sweep. Throws InputError for a key the scene format
/// does not have (the result is re-read with readScene, which checks ranges).
std::string sceneWithOverrides(const std::string& path, const std::vector<std::pair<std::string, double>>& overrides);

}  // namespace tessera

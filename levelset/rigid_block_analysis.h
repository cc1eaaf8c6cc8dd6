#pragma once
#include "levelset/contact_polygons.h"

#include <optional>
#include <string>
#include <vector>

namespace tessera {

/// A rigid motion of one body: velocity of its centroid and angular velocity (directions; the
/// whole motion is scaled so that its largest component is 1, rotations times the bodies' median
/// size).
struct BodyMotion {
  int body = -1;
  Eigen::Vector3d translation{0, 0, 0};
  Eigen::Vector3d rotation{0, 0, 0};
};

/// Kinematic interlocking (docs/check.md), frictionless and infinitesimal, as in Wang et al.,
/// "Design and structural optimization of topological interlocking assemblies" (ACM TOG 38, 2019):
/// with x the free bodies' velocities (the fixed ones held) and A the contact corners' rows of
/// relative normal velocity, (A x)_c = n . (u_second(p) - u_first(p)), the assembly is interlocked
/// when no x with A x >= 0 opens a contact: max sum_c (A x)_c over A x in [0, 1], |x| <= 1, is 0.
/// Motions with A x = 0 slide along every contact and open none (the null space of A, from the
/// eigenvalues of A^T A below 1e-12 of the largest); such sliding modes are counted: only friction
/// holds them (and for translations along plane faces, they are finite motions).
struct InterlockingVerdict {
  bool interlocked = false;         ///< no motion opens a contact
  std::vector<BodyMotion> motion;   ///< when not interlocked: a motion that opens contacts and closes none
  int slidingModes = 0;             ///< independent motions that slide along every contact
  std::vector<BodyMotion> sliding;  ///< one of them (empty above 600 free bodies: counted, not shown)
};
/// The interlocking program's optimum for bodies given by their reference points (`position`, m:
/// rotations turn about them), `fixed` flags and size `length` (m, the L of the columns), over the
/// contact corners: 0 when interlocked, else how much a motion can open the corners (up to their
/// count). For searches over designs (levelset/interlocking_signs.h). `moving`, if given: per body,
/// whether the motion that opens them most moves it.
double largestOpening(const std::vector<Eigen::Vector3d>& position, const std::vector<char>& fixed, double length,
                      const std::vector<ContactCorner>& corners, std::vector<char>* moving = nullptr);

/// Static stability under gravity (-z), docs/check.md. Rigid-block equilibrium, as compas_rbe
/// (Whiting, Ochsendorf & Durand, "Procedural modeling of structurally-sound masonry buildings",
/// ACM TOG 28, 2009) poses it: compressive corner forces within Coulomb's cone (an inscribed pyramid
/// of 8 faces, which needs up to 1 / cos(22.5 deg) = 1.082 times the cone's friction) balance every
/// free body's weight; its least friction by bisection (to 1 % or 1e-3, up to 10). Without friction
/// that decides (Farkas: no admissible motion lowers the weights), and for an interlocked assembly
/// (every admissible motion slides; friction holds it once the blocks wedge). For an assembly with
/// a way out that needs friction, equilibrium alone would accept forces the unstressed blocks cannot
/// get: the verdict is then the elastic settling's (levelset/elastic_settling.h), on the run's
/// contact springs, and so is the least friction.
struct StabilityVerdict {
  bool stable = false;  ///< at the given friction
  /// The least friction it stands at (0: none needed; 1e-3: wedged rigid blocks, any friction);
  /// none: not up to 10, or not searched (settled and not standing: where its branch ended).
  std::optional<double> leastFriction;
  bool searched = false;            ///< the least friction was looked for
  bool settled = false;             ///< decided by the elastic settling
  std::size_t nodes = 0;            ///< its contact springs (surface nodes touching, both ways)
  std::vector<BodyMotion> falling;  ///< settled and not standing: the way the bodies go
  /// Rigid-block equilibrium's least friction, when searched or 0: below it nothing, not even a
  /// prestress, holds the assembly.
  std::optional<double> rigidLeastFriction;
};
/// `findLeastFriction` false: the verdict at `friction` alone (and whether it stands without).
/// `interlocked`: the interlocking verdict on the same corners.
StabilityVerdict checkStability(const Bundle& bundle, const AssemblyLevelSets& levelSets, const std::vector<ContactCorner>& corners,
                                bool interlocked, double friction, bool findLeastFriction = true);

/// Surfaces within this fraction of the bodies' median size touch, for the checks below: the
/// rounding of exported coordinates (6 decimals in metres on 0.1 m parts: 1e-5) passes, a gap of
/// 0.05 mm between 10 mm blocks (4e-3) does not. As ConvexFitOptions::relativeTolerance.
constexpr double kTouchFraction = 1e-4;

/// Both checks of an assembly, as `tessera check`, tile and assemble report them: contacts within
/// kTouchFraction of the bodies' median size, at the given friction coefficient.
struct AssemblyStatics {
  std::size_t pairs = 0, polygons = 0, corners = 0;  ///< touching pairs, contact polygons, their corners
  InterlockingVerdict interlocking;
  StabilityVerdict stability;
  double friction = 0;
  double seconds = 0;  ///< wall-clock time of the contacts, the linear programs and the settling
};
AssemblyStatics analyseAssembly(const Bundle& bundle, const AssemblyLevelSets& levelSets, double friction, bool findLeastFriction = true);

}  // namespace tessera

#pragma once
#include <Eigen/Core>

namespace tessera {

/// How the solver integrates (docs/physics.md). Units in the comments.
struct SolverSettings {
  double density = 2500.0;                      ///< kg/m^3
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};     ///< m/s^2
  double timeStep = 0.0;                        ///< s; 0 = automatic (timeStepFactor x 2 / omega_max)
  /// Fraction of Verlet's stability limit 2 / omega for the stiffest expected contact (one face,
  /// sticking). 0.1 keeps omega dt at 0.2 there (energy kept to ~0.5 % over ten impacts) and leaves
  /// room for contacts up to ten times stiffer (a block clamped on every face) before the limit.
  double timeStepFactor = 0.1;
  double localDamping = 0.0;                    ///< alpha in [0, 1): Cundall's local non-viscous damping
  double viscousDamping = 0.0;                  ///< c, 1/s: global viscous damping F -= c m v, tau -= c I omega
  int threads = 0;                              ///< 0 = all cores
  double broadPhaseMargin = 0.5e-3;             ///< m: bounding boxes are enlarged by this; rebuilt when a body moves 0.4 of it
  double maxPenetration = 0.0;                  ///< m; 0 = a quarter of the thinnest block. Deeper stops the run
  double energyGrowthLimit = 10.0;              ///< stop when kinetic energy exceeds this x the energy supplied
  /// Convex polyhedral shapes (the planar and hex TIS blocks) use their face planes as an exact,
  /// analytic level set instead of the grid; false forces the grid everywhere.
  bool exactConvexLevelSets = true;
};

}  // namespace tessera

#pragma once
#include "geometry/paper_block.h"

#include <Eigen/Core>

namespace tessera {

/// How a World advances (docs/physics.md): explicit velocity-Verlet steps bounded by the fastest
/// contact mode, or implicit increments that find the bodies' balance of forces at their end
/// (backward Euler; quasi-static where the increment is long against the bodies' periods).
enum class SolverMethod { Explicit, Implicit };

/// The implicit method's Newton iteration and increments (docs/physics.md, "Implicit method").
struct ImplicitSettings {
  /// Converged when every free body's force residual is below this x the force scale (the largest
  /// weight or contact force sum of a body) and its torque residual below this x that scale x its
  /// radius. 1e-4 leaves the default test's P_max, K and W within 0.4 % of 1e-6 in half the
  /// iterations (docs/performance.md, "The implicit method").
  double tolerance = 1e-4;
  int maxIterations = 25;  ///< Newton iterations before the increment is cut
  /// s, the longest increment; 0: 1e4 x the explicit method's automatic step (quasi-static on a
  /// slab of the paper's blocks: the inertia of an increment is 1e-3 of its contact forces).
  double maxIncrement = 0.0;
  /// m, the farthest an obstacle (the indenter) moves in one increment; 0: maxTravelRatio x the
  /// thinnest block (10 um on the paper's block).
  double maxTravel = 0.0;
  double maxTravelRatio = 10e-6 / kPaperThickness;
  /// While the obstacles' reactions change smoothly (by at most smoothReactionChange of
  /// themselves over an increment, converged easily), the travel limit grows by doubling to this
  /// many times maxTravel; a change above 4 x smoothReactionChange sets it back.
  double maxTravelGrowth = 2.0;
  double smoothReactionChange = 0.01;
  /// Where equilibrium is lost (an obstacle's reaction drops by more than 4 x smoothReactionChange
  /// of itself in one increment: a slip, a block pushed through), the increment is cut until it is
  /// at most this many times the explicit method's automatic step, so that backward Euler follows
  /// the event as dynamics (its inertia then carries the energy released), and grows back as the
  /// motion dies down.
  double dynamicIncrementRatio = 10.0;
};

/// How the solver integrates (docs/physics.md). Units in the comments.
/// The most threads a run may ask for: a thread pool of more slots than this exhausts memory
/// (TBB sizes its arena by the request, 10^9 slots crashed) and buys nothing on any machine.
constexpr int kMaxThreads = 1024;

struct SolverSettings {
  double density = 2500.0;                      ///< kg/m^3
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};     ///< m/s^2
  double timeStep = 0.0;                        ///< s; 0 = automatic (timeStepFactor x 2 / omega_max)
  /// Fraction of Verlet's stability limit 2 / omega_max, omega_max an upper estimate of the fastest
  /// mode (World::automaticTimeStep). Measured critical factors on the default slab lie at 1.4 and
  /// above for E 3.3-75 GPa and mu 0.19-9 (docs/performance.md, "Stability"); 0.5 keeps a margin
  /// of about 3 and leaves the results within 0.05 % of ten times smaller steps.
  double timeStepFactor = 0.5;
  /// A fixed timeStep above the stability estimate 2 / omega_max (factor 1) is refused unless this
  /// is set: for measuring critical steps (bench/stability_map.cpp), never for results.
  bool allowUnsafeTimeStep = false;
  double localDamping = 0.0;                    ///< alpha in [0, 1): Cundall's local non-viscous damping
  double viscousDamping = 0.0;                  ///< c, 1/s: global viscous damping F -= c m v, tau -= c I omega
  int threads = 0;                              ///< 0 = all cores, at most kMaxThreads
  /// m: bounding boxes are enlarged by this and the pairs found again when a body moves 0.4 of
  /// it; a pair's node candidates are the nodes within 1.25 of it of the other side, found again
  /// when the pair's sides have moved 1.25 / sqrt(3) of it relative to each other. Changes cost,
  /// never results. 0 = broadPhaseMarginRatio x the thinnest block (0.02 mm on the paper's block:
  /// the default test ran fastest at 0.01-0.02 mm, 0.74 x its time at 0.5 mm; docs/performance.md).
  double broadPhaseMargin = 0.0;
  double broadPhaseMarginRatio = 0.02e-3 / kPaperThickness;
  double maxPenetration = 0.0;                  ///< m; 0 = a quarter of the thinnest block. Deeper stops the run
  double energyGrowthLimit = 10.0;              ///< stop when kinetic energy exceeds this x the energy supplied
  /// Convex polyhedral shapes (the planar and hex TIS blocks) use their face planes as an exact,
  /// analytic level set instead of the grid; false forces the grid everywhere.
  bool exactConvexLevelSets = true;
  /// Shapes without exact planes (not convex, or planes off) use their exact mesh level set near
  /// the surface (the distance to the closest triangle, signed by pseudo-normals) instead of the
  /// grid; false leaves them the grid.
  bool exactMeshLevelSets = true;
  SolverMethod method = SolverMethod::Explicit;
  ImplicitSettings implicit;
};

}  // namespace tessera

#pragma once
#include "levelset/bundle.h"
#include "levelset/contact_polygons.h"
#include "levelset/rigid_block_analysis.h"

#include <optional>
#include <vector>

namespace tessera {

/// Whether an assembly built unstressed stands when its weight comes on (docs/check.md, "Stability
/// under gravity"). The rigid bodies rest on the LS-DEM run's own contact springs, at the surface
/// nodes that touch another body (contactNodes): a normal spring that carries no tension and a
/// tangential one of the same stiffness (the run's k_t / k_n = 1), both in proportion to the
/// node's area, the tangential force capped by Coulomb's law at mu times the normal one. The weight
/// comes on in proportion from zero on contacts at zero gap, so the solution is radial,
/// u(lambda) = lambda u(1): one equilibrium R(u) = 0 at the full weight (no tangential spring
/// unloads on the way), whose existence does not depend on the stiffness's scale (forces go as k u).
/// Infinitesimal: the contact normals and lever arms are those of the assembly as built.
///
/// The equilibria are followed from every tangential spring sticking down in friction, each from
/// the last: relaxed from it by pseudo-transient continuation, or else by Tresca's fixed point,
/// whose convex minima also show a fall (the weights' work unbounded); the branch ends at the
/// least friction, below which no equilibrium is found near it: the bodies fall.
/// `findLeastFriction` false: the same steps, stopped once `friction` is passed.
struct ElasticSettling {
  bool stands = false;  ///< at the friction asked for
  /// The least friction it stands at (the last failed step within 2 % below it): 0 when it stands
  /// without friction; else when searched, or where its branch ended when it does not stand at the
  /// friction asked for; none when it does not stand at the start, max(10, friction).
  std::optional<double> leastFriction;
  std::vector<BodyMotion> falling;  ///< when it does not stand: the last failed step, the bodies' way down
  /// False when at the start (friction max(10, friction)) neither an equilibrium was found nor a fall
  /// shown (every solver stalled): then `stands` false says only that none was found.
  bool decided = true;
};
/// The solvers' step limits (docs/check.md, "The elastic settling"): Newton steps per convex
/// minimum, relaxation steps per equilibrium and those without halving the out-of-balance force,
/// rounds of Tresca's fixed point.
struct SettlingBudget {
  int newtonSteps = 100;
  int relaxSteps = 100;
  int stall = 15;
  int rounds = 5;
};
ElasticSettling settleElastically(const Bundle& bundle, const std::vector<ContactNode>& nodes, double friction,
                                  bool findLeastFriction, const SettlingBudget& budget = {});

}  // namespace tessera

#pragma once
#include "solver/contact_bars.h"
#include "solver/contact_parameters.h"
#include "solver/obstacles.h"
#include "solver/pair_state.h"
#include "solver/pair_view.h"
#include "solver/rigid_bodies.h"
#include "solver/solver_settings.h"
#include "solver/travel.h"

#include "levelset/body.h"
#include "levelset/shape.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

/// The run cannot go on: a non-finite state, a penetration beyond the bound, or kinetic energy
/// growing beyond the energy supplied. what() names the time, the body and the quantity.
class SolverInstability : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Energy bookkeeping since the start, J (docs/physics.md, "Energy balance").
struct EnergyBudget {
  double kinetic = 0.0;
  double elastic = 0.0;         ///< stored in the contact springs (normal and tangential)
  double gravityWork = 0.0;     ///< work done by gravity
  double externalWork = 0.0;    ///< work done by the prescribed obstacles (the indenter)
  double initial = 0.0;         ///< kinetic + elastic at the start
  double friction = 0.0;        ///< dissipated by sliding at the Coulomb cap
  double damping = 0.0;         ///< dissipated by local and viscous damping and the normal viscosity
  double retiredKinetic = 0.0;  ///< carried off by bodies taken out of the computation (retired)
  double projection = 0.0;      ///< removed by changes of projected contact areas (ContactTally::projection)
  /// What went in minus what is stored, dissipated or carried off: zero but for the integrator's
  /// error (a time-step quantity: it shrinks with dt^2).
  double residual() const {
    return initial + gravityWork + externalWork - (kinetic + elastic + friction + damping + retiredKinetic + projection);
  }
};

/// What the implicit method has done (WorldState::implicit): increments are the World's steps.
struct ImplicitCounts {
  double increment = 0.0;  ///< s, the next increment's duration (0: the longest allowed)
  double travelFactor = 1.0;  ///< the obstacles' travel limit, of ImplicitSettings::maxTravel (1 to maxTravelGrowth)
  double largestReaction = 0.0;  ///< N, the largest obstacle reaction at a converged increment
  long iterations = 0;     ///< Newton iterations, line-search trials not counted
  long cutbacks = 0;       ///< increments cut to a quarter for want of convergence
  /// Increments in which inertia carried more than 1 % of the force scale: where equilibrium was
  /// lost (a slip, a block falling out) and the run went through the event with dynamics.
  long dynamicIncrements = 0;
};

/// Everything a World changes as it runs but its contact pairs, which it keeps in its own form
/// (WorldState adds them).
struct WorldRunState {
  RigidBodies bodies;
  std::vector<SphereObstacle> spheres;
  std::vector<PlaneObstacle> planes;
  std::vector<Eigen::Vector3d> builtPosition, builtSphereCentre;
  std::vector<Eigen::Quaterniond> builtOrientation;
  bool pairsValid = false;
  std::vector<Eigen::Vector3d> force, torque, contactForce, contactTorque, sphereReaction, dampingForce, dampingTorque;
  bool forcesValid = false;
  std::vector<Eigen::Vector3d> startPosition;
  double initialEnergy = 0, externalWork = 0, friction = 0, damping = 0, retiredKinetic = 0, projection = 0, mostSupplied = 0,
         time = 0;
  long steps = 0;  ///< explicit steps, or implicit increments
  ImplicitCounts implicit;
};

/// Everything a World changes as it runs: saved in checkpoints, restored to resume bit-identically.
struct WorldState : WorldRunState {
  std::vector<PairState> pairs;  ///< with their springs and last forces
};

struct PairContacts;  // the solver's own record of a pair (solver/pair_contacts.h, private to the solver)
struct ShapeModel;

/// An LS-DEM world: rigid bodies placed among shapes, analytic obstacles, node-vs-level-set contacts,
/// velocity-Verlet time integration with a symplectic free-rotation splitting.
class World {
public:
  /// The bodies placed among the shapes (an asset bundle's Bundle::shapes and Bundle::bodies, or
  /// any built in memory); std::out_of_range for a body whose shape index is not among them.
  World(const std::vector<Shape>& shapes, const std::vector<Body>& bodies, const ContactParameters& parameters,
        const SolverSettings& settings);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  int addSphere(const SphereObstacle& sphere);  ///< returns its index
  int addPlane(const PlaneObstacle& plane);
  SphereObstacle& sphere(int k) { return state_.spheres[k]; }
  const SphereObstacle& sphere(int k) const { return state_.spheres[k]; }

  /// Body state, read-only: change it through setPose and setVelocity.
  const RigidBodies& bodies() const { return state_.bodies; }
  /// Body i's pose between steps (m; unit quaternion, body -> world). Its pairs are found afresh
  /// and the forces evaluated again (no spring is loaded by the jump); the energy the jump stores
  /// in the contacts, or releases, is booked as supplied (EnergyBudget::initial).
  /// std::invalid_argument for a body that does not move (a support, a retired body) or a value
  /// that is not finite.
  void setPose(int i, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation);
  /// Body i's velocity (m/s) and angular momentum (kg m^2/s, body frame) between steps; the forces
  /// (viscous terms depend on them) are evaluated again at the next step, and the change of kinetic
  /// energy is booked as supplied. Throws as setPose.
  void setVelocity(int i, const Eigen::Vector3d& velocity, const Eigen::Vector3d& angularMomentum);

  double time() const { return state_.time; }
  long stepCount() const { return state_.steps; }
  double timeStep() const { return dt_; }
  /// The contact law's parameters and the settings, as resolved (broadPhaseMargin > 0).
  const ContactParameters& parameters() const { return parameters_; }
  const SolverSettings& settings() const { return settings_; }
  /// timeStepFactor x 2 / omega_max, omega_max an upper estimate of the fastest mode of any free
  /// body: its whole surface in sticking contact with bodies like itself moving the other way.
  double automaticTimeStep() const { return automaticDt_; }

  /// Advances one step (SolverSettings::method): an explicit time step, or an implicit increment
  /// (the bodies' balance of forces at its end; timeStep() is then the last increment's duration).
  /// Throws SolverInstability instead of producing garbage.
  void step();
  const ImplicitCounts& implicitCounts() const { return state_.implicit; }
  /// m, how far an obstacle moving at `speed` (m/s) goes in one step: speed x the time step, or
  /// for the implicit method the increment's limit (the travel limit, or the longest increment).
  double travelPerStep(double speed) const;

  /// The changing state, and its restoration into a World made from the same shapes, bodies and settings.
  /// restore() checks the state first (sizes, indices, finite values): std::invalid_argument
  /// naming what is wrong, and this World unchanged.
  WorldState state() const;
  void restore(const WorldState& state);
  void checkState(const WorldState& state) const;

  /// Takes a body out of the computation (a block that has fallen clear): it is frozen where it
  /// is, no longer integrated and no longer in any pair; its kinetic energy is booked as carried off.
  void retireBody(int i);
  bool isRetired(int i) const { return state_.bodies.retired[i] != 0; }
  /// A support of the assembly: fixed from the start.
  bool isSupport(int i) const { return state_.bodies.fixed[i] != 0; }
  /// World-aligned box around body i's shape (ShapeModel::box), enlarged by `margin` (m).
  Eigen::AlignedBox3d bodyBox(int i, double margin) const;
  /// Each body's position when the World was made, m.
  const std::vector<Eigen::Vector3d>& startPositions() const { return state_.startPosition; }
  /// The smallest extent of body i's box in its own frame, m (the thickness of a slab block).
  double bodySize(int i) const;

  /// Contact force and torque (about the centroid) on each body from the last evaluation, N and N m.
  const std::vector<Eigen::Vector3d>& contactForces() const { return state_.contactForce; }
  const std::vector<Eigen::Vector3d>& contactTorques() const { return state_.contactTorque; }
  /// Force of the bodies on sphere k (the indenter's reaction), N.
  Eigen::Vector3d sphereReaction(int k) const { return state_.sphereReaction[k]; }
  /// The candidate pairs of the last evaluation (touching or near), and pair k of them as seen
  /// from outside the solver. Right after restore(), until the next evaluation, a pair's normal
  /// force, force point and sliding nodes are 0 (a PairState does not keep them).
  int pairCount() const;
  PairView pair(int k) const;
  EnergyBudget energy() const;
  double maxPenetration() const;  ///< m, deepest node in the last evaluation

private:
  friend struct WorldInternals;  // the solver's own tests and benchmarks (solver/world_internals.h)
  /// A pair's normal stiffness k_n, N/m^3 (ContactParameters::stiffnessRule; an obstacle's own
  /// stiffness factor included).
  double normalStiffness(const PairContacts& pair) const;
  void evaluateForces(double springStep);
  void explicitStep();
  // The implicit method (solver/implicit_increment.cpp).
  struct ImplicitWork;
  void implicitStep();
  void numberFreeBodies();
  double implicitLongestIncrement() const;
  double implicitIncrementLimit() const;
  double implicitTravelLimit() const;
  double implicitDynamicIncrement() const;
  bool solveIncrement(double dt, int& iterations);
  double evaluateIncrement(double dt, bool withMatrix);
  void commitIncrement(double dt, int iterations, bool lost);
  bool lostEquilibrium() const;
  void updatePairs();
  double stiffnessScale(const PairContacts& pair) const;
  double candidateBand() const;
  void checkStability();

  std::vector<ShapeModel> shapes_;
  WorldRunState state_;  // everything that changes as it runs but the pairs: state() and restore() copy it whole
  std::vector<PairContacts> pairs_;  // sorted by (a, b): state() keeps their PairState, restore() rebuilds the rest
  ContactParameters parameters_;
  SolverSettings settings_;
  struct ThreadArena;
  std::unique_ptr<ThreadArena> arena_;  // the threads the contact loop runs on
  std::unique_ptr<ImplicitWork> implicit_;  // the implicit method's scratch (derived, not state)
  BodyKinematics kinematics_;           // of state_.bodies at the last evaluation (derived, not state)
  Travel travel_;                       // of the bodies and spheres, to the last evaluation (derived, not state)
  std::vector<double> bodyRadius_;      // m, each body's ShapeModel::radius
  ContactBars bars_;                    // the bar rule's geometry, from the start poses
  double penetrationLimit_ = 0.0, thinnest_ = 0.0;
  double dt_ = 0.0, automaticDt_ = 0.0;
};

}  // namespace tessera

#pragma once
#include "levelset/bundle.h"
#include "run/stop_reason.h"
#include "run/scene.h"
#include "solver/world.h"

#include <functional>
#include <string>
#include <vector>

namespace tessera {

/// One point of the load-deflection record (docs/outputs.md). Counts are stored as numbers.
struct CurveSample {
  double time = 0;                ///< s since the start of loading
  double delta = 0;               ///< m, indenter travel since first contact
  double load = 0;                ///< N, P: the bodies' push on the indenter (upward)
  double blockDisplacement = 0;   ///< m, delta_b: downward displacement of the loaded block since settling
  double indenterPenetration = 0; ///< m, deepest node inside the indenter (delta - delta_b, but for rotation)
  double contacts = 0;            ///< node contacts, the indenter's included
  double blockContacts = 0;       ///< node contacts between bodies
  double slidingContacts = 0;     ///< of those, at the Coulomb cap
  double loadedContacts = 0;      ///< node contacts between the loaded block and other bodies
  double loadedSliding = 0;       ///< of those, at the Coulomb cap
  double kinetic = 0;             ///< J; the energies are since the start of the run (settling included)
  double externalWork = 0;        ///< J, work done by the indenter
  double elastic = 0;             ///< J, stored in the contacts
  double friction = 0;            ///< J, dissipated by sliding
  double damping = 0;             ///< J, dissipated by damping
  double gravityWork = 0;         ///< J, work done by gravity
  double retiredKinetic = 0;      ///< J, carried off by retired bodies
  double projection = 0;          ///< J, removed by changes of projected contact areas
  double residual = 0;            ///< J, EnergyBudget::residual
  double indenterSpeed = 0;       ///< m/s, the indenter's downward speed at the sample
};

/// A sample's energy fields from a World's budget: the one mapping of the budget's quantities to
/// the curve's energy columns (curveColumns(), unit J), which Python's Simulation.energy reads too.
void setEnergies(CurveSample& sample, const EnergyBudget& energy);

/// The contact of one pair at a snapshot (a force-chain link).
struct ForceLink {
  int a = -1, b = -1;            ///< bodies; b < 0: the indenter
  Eigen::Vector3d point{0, 0, 0};  ///< m, mean contact point weighted by normal force
  Eigen::Vector3d force{0, 0, 0};  ///< N, on body a
  Eigen::Vector3d normalForce{0, 0, 0};  ///< N, its part along the contact normals (force - normalForce: friction)
  int nodeContacts = 0;          ///< node contacts of the pair
  double area = 0;               ///< m^2, their effective (projected) area
  int slidingNodes = 0;          ///< of them, at the Coulomb cap
  double normalStiffness = 0;    ///< N/m^3, the pair's k_n (material.stiffness_rule)
};

/// Body poses and contact forces at one moment (for the ParaView time series).
struct Snapshot {
  double delta = 0;  ///< m
  double load = 0;   ///< N
  std::vector<Eigen::Vector3d> position;        ///< m, each body's centroid
  std::vector<Eigen::Quaterniond> orientation;  ///< body to world
  std::vector<ForceLink> forces;
  std::vector<Eigen::Vector3d> velocity;        ///< m/s, each body's centroid
  Eigen::Vector3d indenter{0, 0, 0};            ///< m, the indenter's centre
};

/// A block out of the slab (assembly_state.h): fallen (no chain of block contacts holds it to a
/// support) or pushed through (still touching, but moved past its neighbours by its own size).
struct FallenBody {
  std::string name;
  double delta = 0;      ///< m, when it left: lost its last contact path to a support, or was pushed through
  bool retired = false;  ///< taken out of the computation, having left the assembly
  bool touching = false; ///< pushed through: still in contact with blocks
};

/// What a run produced.
struct IndentationRecord {
  double settleTime = 0;   ///< s of simulated time spent settling
  long settleSteps = 0;
  bool settled = false;    ///< false: settle_max_time ran out first
  int target = -1;
  std::string targetName;
  double thickness = 0;    ///< m, h: the loaded block's extent along the loading direction
  double deltaMax = 0;     ///< m, where the run stops at the latest
  // As resolved from the scene's ratios (docs/scene.md); set by runIndentation, not stored.
  double indenterRadius = 0;  ///< m
  double indenterSpeed = 0;   ///< m/s
  double settleKinetic = 0;   ///< J, the settle threshold
  double settleMaxTime = 0;   ///< s, the longest settling
  int sunkWhileSettling = 0;  ///< free bodies that moved down by more than fallenClearance x their size while settling
  std::vector<CurveSample> curve;
  std::vector<Snapshot> snapshots;
  std::vector<FallenBody> fallen;  ///< as of the last sample
  StopReason stopReason = StopReason::Running;
  long steps = 0;          ///< all steps (implicit: increments), settling included
  double timeStep = 0;     ///< s (implicit: the last increment's duration)
  bool implicit = false;   ///< the World's method was implicit (solver.method)
  ImplicitCounts implicitCounts;  ///< the implicit method's iterations, cut-backs, dynamic increments
  double wallSeconds = 0;

  /// The run has ended for good: at delta_max, on failure, or as its sample hook asked (not when
  /// interrupted, unstable, or still running).
  bool finished() const { return isComplete(stopReason); }
};

/// The record's account of the World's stepping: steps (increments), the last time step, the
/// method and the implicit method's counts.
void recordStepping(IndentationRecord& record, const World& world);

/// Progress while running (called every output.progressSeconds of wall time).
struct Progress {
  double delta, load, kinetic, externalWork;
  long contacts, steps;
  double stepsPerSecond, etaSeconds;
  bool settling;  ///< still settling: no load yet, the ETA counts the loading to come
  /// s of wall time, while settling: the most the settling can still take (to its time limit, at
  /// this session's rate); it ends sooner once the slab is at rest. 0 once loading.
  double settleEtaSeconds = 0;
};

/// Where the protocol is: enough, with the World's state and the record, to resume it exactly.
struct IndentationState {
  int phase = 0;             ///< 0 settling, 1 loading, 2 finished
  int sphere = -1;           ///< the indenter's index in the World
  double loadStart = 0;      ///< s, when loading began
  double contactTravel = -1; ///< m, indenter travel at first contact (< 0: not yet)
  double peak = 0;           ///< N, largest load so far
  double nextSample = 0, nextSnapshot = 0;  ///< m of indenter path since first contact (= delta while it only goes down)
  double quietFrom = -1;     ///< m of path since which the load has stayed below 1 % of the peak (< 0: it has not)
  /// The indenter's travel (down) and path (|travel|, summed) since loading began, m, are
  /// travelBase + v (t - speedSince) and pathBase + |v| (t - speedSince), v its current downward
  /// speed: the bases move when a sample hook changes v. Without a change: v t, the same number.
  double travelBase = 0, pathBase = 0;
  double speedSince = 0;     ///< s, when the indenter's velocity last changed (loadStart at first)
  double contactPath = -1;   ///< m, indenter path at first contact (< 0: not yet)
  /// The adaptive loading rate is over: the load fell below half its largest value, or a sample
  /// hook set the indenter's speed.
  bool rateAdapted = false;
  std::vector<Eigen::Vector3d> settledPosition;
  std::vector<double> outAt;  ///< m of delta per body: when it lost its last contact path to a support or was pushed through (< 0: in)
};

/// What a sample hook may change, from the next step on.
struct IndentationControl {
  double indenterSpeed = 0;  ///< m/s, downward; negative lifts the indenter, 0 holds it (as it is on entry)
  bool stop = false;         ///< true: stop the run here (stop reason "requested")
};

/// What the caller hears while the test runs. Every hook is optional.
struct RunHooks {
  std::function<void(const Progress&)> progress;
  std::function<bool()> interrupted;           ///< true: stop now (the record stays valid)
  std::function<void(const IndentationState&)> checkpoint;  ///< every checkpointSeconds of wall time and at the stop
  std::function<void(const std::string&)> warning;          ///< once per session and kind (e.g. loading too fast)
  /// After every curve sample while loading (the sample is record.curve.back()): may change the
  /// indenter's speed (load-unload cycles, holds, force control) or stop the run.
  std::function<void(const CurveSample&, IndentationControl&)> sample;
  double checkpointSeconds = 30.0;
};

/// The indentation test (docs/physics.md, "Protocol"): settle under gravity until the kinetic
/// energy is below protocol.settleKinetic (or settleMaxTime passes); put the spherical indenter
/// just above the top of the target block; push it down at constant speed, sampling the curve.
/// At each sample, bodies that have fallen are listed and those that have left the assembly
/// retired (assembly_state.h: never a body touching a block). Stops at deltaMax (0: 2 h of the
/// loaded block), or (stopOnFailure) once the load has stayed below 1 % of its peak over
/// quietTravel x h of indenter path and every free body is at rest or fallen, when `interrupted`
/// returns true, or when the sample hook asks. Samples and snapshots are taken every so much
/// indenter path (equal to delta while the indenter only goes down), so an unloading is recorded
/// too: delta then decreases.
/// SolverInstability propagates (the caller keeps what was recorded so far through `record`).
/// Runs (or, from a restored World, record and state, resumes) the test.
void runIndentation(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                    IndentationState& state, const RunHooks& hooks);



}  // namespace tessera

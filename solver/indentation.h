#pragma once
#include "levelset/bundle.h"
#include "solver/scene.h"
#include "solver/world.h"

#include <functional>
#include <string>
#include <vector>

namespace tessera {

/// One point of the load-deflection record.
struct CurveSample {
  double time = 0;          ///< s since the start of loading
  double delta = 0;         ///< m, indenter travel since first contact
  double load = 0;          ///< N, P: the bodies' push on the indenter (upward)
  double kinetic = 0;       ///< J
  double externalWork = 0;  ///< J, work done by the indenter
  double elastic = 0;       ///< J, stored in the contacts
  long contacts = 0;        ///< node contacts
  double targetDrop = 0;    ///< m, downward displacement of the loaded block since settling
};

/// The resultant contact force of one pair at a snapshot (a force-chain link).
struct ForceLink {
  int a = -1, b = -1;            ///< bodies; b < 0: the indenter
  Eigen::Vector3d point{0, 0, 0};  ///< m, mean contact point weighted by normal force
  Eigen::Vector3d force{0, 0, 0};  ///< N, on body a
};

/// Body poses and contact forces at one moment (for the ParaView time series).
struct Snapshot {
  double delta = 0;  ///< m
  double load = 0;   ///< N
  std::vector<Eigen::Vector3d> position;
  std::vector<Eigen::Quaterniond> orientation;
  std::vector<ForceLink> forces;
};

struct FallenBody {
  std::string name;
  double delta;  ///< m, when it was found fallen (and retired)
};

/// What a run produced.
struct IndentationRecord {
  double settleTime = 0;   ///< s of simulated time spent settling
  long settleSteps = 0;
  bool settled = false;    ///< false: settle_max_time ran out first
  int target = -1;
  std::string targetName;
  std::vector<CurveSample> curve;
  std::vector<Snapshot> snapshots;
  std::vector<FallenBody> fallen;
  std::string stopReason;  ///< "delta_max", "failure", "interrupted"
  long steps = 0;          ///< all steps, settling included
  double timeStep = 0;     ///< s
  double wallSeconds = 0;
};

/// Progress while running (called every output.progressSeconds of wall time).
struct Progress {
  double delta, load, kinetic, externalWork;
  long contacts, steps;
  double stepsPerSecond, etaSeconds;
};

/// Where the protocol is: enough, with the World's state and the record, to resume it exactly.
struct IndentationState {
  int phase = 0;             ///< 0 settling, 1 loading, 2 finished
  int sphere = -1;           ///< the indenter's index in the World
  double loadStart = 0;      ///< s, when loading began
  double contactTravel = -1; ///< m, indenter travel at first contact (< 0: not yet)
  double peak = 0;           ///< N, largest load so far
  double nextSample = 0, nextSnapshot = 0;  ///< m of delta
  double fallenDistance = 0; ///< m
  double targetZ0 = 0;       ///< m, settled height of the loaded block
  std::vector<Eigen::Vector3d> settledPosition;
};

/// What the caller hears while the test runs.
struct RunHooks {
  std::function<void(const Progress&)> progress;
  std::function<bool()> interrupted;           ///< true: stop now (the record stays valid)
  std::function<void(const IndentationState&)> checkpoint;  ///< every checkpointSeconds of wall time and at the stop
  double checkpointSeconds = 30.0;
};

/// The indentation test (DESIGN §5): settle under gravity until the kinetic energy is below
/// protocol.settleKinetic (or settleMaxTime passes); put the spherical indenter just above the top
/// of the target block; push it down at constant speed, sampling the curve; retire bodies that
/// have fallen `fallenDistance` below their settled position; stop at deltaMax, or (stopOnFailure)
/// once the loaded block has fallen and the load is below 1 % of its peak, or when `interrupted`
/// returns true. SolverInstability propagates (the caller keeps what was recorded so far through
/// `record`).
/// Runs (or, from a restored World, record and state, resumes) the test.
void runIndentation(World& world, const Bundle& bundle, const Scene& scene, IndentationRecord& record,
                    IndentationState& state, const RunHooks& hooks);

/// The free body nearest the bodies' centre in x and y (the default target).
int centralFreeBody(const World& world);

}  // namespace tessera

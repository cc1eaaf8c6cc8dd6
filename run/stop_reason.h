#pragma once
#include <optional>
#include <string>

namespace tessera {

/// Why a run stopped, or that it has not. Files (summary.json, results.h5, checkpoint.h5, a sweep's
/// tables) carry its name: "running", "delta_max", "failure", "requested", "interrupted",
/// "instability".
enum class StopReason {
  Running,      ///< not stopped yet
  DeltaMax,     ///< the indenter reached delta_max
  Failure,      ///< the load was lost and every free body came to rest or out (protocol.stop_on_failure)
  Requested,    ///< the sample hook asked to stop
  Interrupted,  ///< Ctrl-C, a signal, or a sample hook's bad speed: resumable from its checkpoint
  Instability,  ///< the solver stopped it (SolverInstability)
};

const char* stopReasonName(StopReason reason);
/// The reason of a name; "" (what a checkpoint of a running run held before the names) is Running.
std::optional<StopReason> parseStopReason(const std::string& name);

/// The run has ended for good, the same for a run, its resume, a sweep and Python: at delta_max, on
/// failure, or as its sample hook asked (not when interrupted, unstable, or still running).
inline bool isComplete(StopReason reason) {
  return reason == StopReason::DeltaMax || reason == StopReason::Failure || reason == StopReason::Requested;
}

}  // namespace tessera

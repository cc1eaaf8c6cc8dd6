#pragma once
#include "run/sweep.h"

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tessera::tools {

/// Submits a sweep's batch script with `sbatch --parsable --array=SPEC [options] SCRIPT`; returns the
/// job id. InputError when sbatch is not found or refuses (with what it said).
std::string submitSlurmArray(const std::string& script, const std::string& arraySpec,
                             const std::vector<std::string>& options);

/// Slurm's state of the array tasks it still knows of this user's jobs, as squeue reports them
/// (PENDING, RUNNING, COMPLETED, CANCELLED, TIMEOUT, ...), by (array job id, task id). Slurm
/// forgets finished jobs after its MinJobAge (300 s by default): then only the case's files tell.
struct SlurmTaskStates {
  bool available = false;  ///< squeue answered
  std::string problem;     ///< why not, when it did not
  std::map<std::pair<std::string, int>, std::string> state;
};
SlurmTaskStates querySlurmTasks();

/// Where Slurm's state leaves a task: Queued (it will run), Running (running, suspended,
/// completing), nothing (ended, or unknown to Slurm).
std::optional<CaseState> slurmTaskPhase(const std::string& state);

}  // namespace tessera::tools

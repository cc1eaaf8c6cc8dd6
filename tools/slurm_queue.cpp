#include "tools/slurm_queue.h"

#include "io/input_error.h"
#include "tools/child_process.h"

#include <set>
#include <sstream>

namespace tessera::tools {

namespace {

// The line of a command's messages that says what went wrong: the last naming an error, else the first.
std::string errorLine(const std::string& text) {
  std::istringstream lines(text);
  std::string line, first, error;
  while (std::getline(lines, line)) {
    if (first.empty()) first = line;
    if (line.find("error") != std::string::npos) error = line;
  }
  return !error.empty() ? error : !first.empty() ? first : "no message";
}

}  // namespace

std::string submitSlurmArray(const std::string& script, const std::string& arraySpec,
                             const std::vector<std::string>& options) {
  std::vector<std::string> command{"sbatch", "--parsable", "--array=" + arraySpec};
  command.insert(command.end(), options.begin(), options.end());
  command.push_back(script);
  const CommandOutput sbatch = runCommand(command);
  if (sbatch.status == 127)
    throw InputError("sbatch not found: --slurm submits from a machine with Slurm's commands (a login node); add "
                     "--dry-run to write the batch script only, or leave out --slurm to run the cases here");
  // --parsable prints "JOBID" or "JOBID;CLUSTER".
  const std::string id = sbatch.out.substr(0, sbatch.out.find_first_of(";\n"));
  if (sbatch.status != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw InputError("sbatch did not submit " + script + " (exit status " + std::to_string(sbatch.status) + "): " +
                     errorLine(sbatch.err + sbatch.out) + "; fix what it names (a --partition, --time or --sbatch option, "
                     "or Slurm's configuration) and submit with --resubmit");
  return id;
}

SlurmTaskStates querySlurmTasks() {
  SlurmTaskStates states;
  // -r: one line per array task; --states=all: finished tasks too, while Slurm keeps them.
  const CommandOutput squeue = runCommand({"squeue", "--me", "-h", "-r", "--states=all", "-o", "%F %K %T"});
  if (squeue.status != 0) {
    states.problem = squeue.status == 127 ? "squeue not found" : errorLine(squeue.err);
    return states;
  }
  states.available = true;
  std::istringstream lines(squeue.out);
  std::string job, task, state;
  while (lines >> job >> task >> state)
    if (task.find_first_not_of("0123456789") == std::string::npos) states.state[{job, std::stoi(task)}] = state;
  return states;
}

std::optional<CaseState> slurmTaskPhase(const std::string& state) {
  static const std::set<std::string> queued{"PENDING", "REQUEUED", "REQUEUE_FED", "REQUEUE_HOLD", "RESV_DEL_HOLD"};
  static const std::set<std::string> running{"RUNNING", "CONFIGURING", "COMPLETING", "RESIZING", "SUSPENDED",
                                             "STAGE_OUT", "SIGNALING", "STOPPED"};
  if (queued.count(state)) return CaseState::Queued;
  if (running.count(state)) return CaseState::Running;
  return std::nullopt;
}

}  // namespace tessera::tools

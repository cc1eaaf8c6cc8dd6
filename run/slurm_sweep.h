#pragma once
#include <string>
#include <vector>

namespace tessera {

/// How a sweep's cases go to Slurm: the sbatch options of its batch script ("" or 0: Slurm's own
/// default, the partition's).
struct SlurmSettings {
  std::string partition;                  ///< --partition
  std::string timeLimit;                  ///< --time per case: MM, HH:MM:SS or D-HH:MM:SS
  int cpusPerTask = 1;                    ///< --cpus-per-task, also the threads of each case's run
  int maxConcurrent = 0;                  ///< cases running at once (the %K of --array); 0 no limit
  std::vector<std::string> extraOptions;  ///< further sbatch options, as written after #SBATCH
};

/// InputError naming a setting Slurm would refuse, or a folder path a batch script cannot hold.
void checkSlurmSettings(const SlurmSettings& settings, const std::string& folder);

/// The --array value for these case numbers: ranges joined by commas, "0-3,7,9-10", then "%K"
/// when maxConcurrent > 0.
std::string slurmArraySpec(std::vector<int> caseNumbers, int maxConcurrent);

/// The batch script of the sweep folder (an absolute path), written to folder/slurm/sweep.sbatch:
/// one array task a case, the task id N running case_N through `tessera sweep FOLDER --case N`
/// (which resumes a case from its checkpoint), SIGTERM 120 s before the time limit so that a case
/// checkpoints before it is killed, requeued on preemption. `tessera` is the absolute path of the
/// executable the tasks run.
std::string slurmSweepScript(const std::string& folder, const std::string& tessera, const SlurmSettings& settings,
                             const std::vector<int>& caseNumbers);

/// One submission of the sweep: its job id and the cases (numbers) it runs.
struct SlurmJob {
  std::string id;
  std::vector<int> cases;
};

/// What folder/slurm/jobs.json records: the settings of the last submission and every
/// submission, oldest first.
struct SlurmRecord {
  SlurmSettings settings;
  std::vector<SlurmJob> jobs;
};

/// The record of the sweep folder; empty (no jobs) when it was never submitted. InputError when
/// the file is corrupt.
SlurmRecord readSlurmRecord(const std::string& folder);

void writeSlurmRecord(const std::string& folder, const SlurmRecord& record);

}  // namespace tessera

#pragma once
#include <string>
#include <vector>

namespace tessera {

/// One swept scene key and its values (SI).
struct SweepAxis {
  std::string key;  ///< table.key of the scene
  std::vector<double> values;
};

/// "KEY=v1,v2,..." or "KEY=first:last:count" (count values evenly spaced, ends included); KEY
/// table.key or one of the short names E, mu, speed, radius, density. InputError naming the
/// problem, also for more than `maxCases` values.
SweepAxis parseSweepAxis(const std::string& text, long maxCases);

/// One case of a sweep: its values (one per axis), the text of its scene, its folder.
struct SweepCase {
  std::vector<double> values;
  std::string scene;
  std::string dir;
};

/// What a sweep is: a base scene, a preset over every case, the axes, grid or zipped.
struct SweepPlan {
  std::string scene;   ///< base scene file
  std::string preset;  ///< "" for none
  std::vector<SweepAxis> axes;
  bool zip = false;    ///< the k-th value of every axis together, instead of their Cartesian product
  long maxCases = 1000;
};

/// The cases of a plan, the first axis varying slowest: each the base scene with the preset's keys
/// and then the case's values (a --set of the preset's key wins), each checked to be a valid scene
/// before anything is made. InputError for more than maxCases cases, unequal zipped axes, a case
/// that is not a valid scene.
std::vector<SweepCase> sweepCases(const SweepPlan& plan);

/// Makes (or finds again) the sweep folder `dir` for the cases: a sweep folder is one study (one
/// base scene and preset, one set of keys), each case folder holding one set of values for good
/// (sweep.json lists them); cases already there are found by their values and must hold the same
/// scene; new values are refused unless `extend`. Writes sweep.json first, then each new case's
/// scene.toml. Returns the cases with their folders. The caller holds the folder's lock.
std::vector<SweepCase> placeSweepCases(const std::string& dir, const SweepPlan& plan, std::vector<SweepCase> cases,
                                       bool extend);

/// A case's run is complete (its summary.json says it stopped at delta_max or by failure).
bool sweepCaseComplete(const std::string& runDir);

/// The cases of the sweep folder `dir` in the order its sweep.json lists them: values, folder, and
/// the text of the case's scene.toml. InputError when `dir` is not a sweep folder or its manifest
/// is corrupt.
std::vector<SweepCase> readSweepFolder(const std::string& dir);

/// The number N of a case folder .../case_N (the Slurm array index of that case).
int sweepCaseNumber(const std::string& caseDir);

/// Where a case stands: from its files alone (whatever ran it: this machine or a cluster), or, for
/// Queued and Unknown, from Slurm's queue as `tessera sweep --status` reads it.
enum class CaseState {
  Complete,     ///< its summary.json says it stopped for good (isComplete, run/stop_reason.h)
  Running,      ///< its runner holds the case's lock on this machine, or started it on another machine
  Interrupted,  ///< stopped by SIGINT or SIGTERM (Ctrl-C, time limit, preemption, cancel), or its runner
                ///< was killed after a checkpoint: resumes from its checkpoint
  Failed,       ///< its run ended with an error (exit status 2 input, 3 unstable, killed by another
                ///< signal), or its runner died before a checkpoint
  Missing,      ///< never started
  Queued,       ///< Slurm holds its task, not started yet
  Unknown,      ///< submitted to Slurm, which cannot say now whether it still holds it
};
const char* caseStateName(CaseState state);

/// A case's state and what case_N/attempt.json records of its last attempt: written by the runner
/// when it starts the case (state "started") and again when the run ends ("ended", exit status).
struct CaseStatus {
  CaseState state = CaseState::Missing;
  int exitStatus = -1;   ///< of the last attempt that ended; -1 when none did
  std::string slurmJob;  ///< the Slurm job (JOB_TASK) of the last attempt, "" when not a Slurm task
  std::string host;      ///< where the last attempt ran
  bool startedElsewhere = false;  ///< Running because an attempt started on another host and has not ended
};
CaseStatus sweepCaseStatus(const std::string& caseDir);

/// The same, once the attempt that started elsewhere is known to be over (its Slurm task gone):
/// interrupted when it left a checkpoint, else failed.
CaseState deadAttemptState(const std::string& caseDir);

/// Records the start (exitStatus < 0) or the end of an attempt at the case in case_N/attempt.json,
/// with this host, this process and `slurmJob` ("" when not a Slurm task).
void recordCaseAttempt(const std::string& caseDir, int exitStatus, const std::string& slurmJob);

/// The table of response parameters of every complete case in the sweep folder (sweep.csv,
/// sweep.h5); an interrupted or failed case is never tabled. Returns the number tabled. Safe to
/// call from several processes at once (cluster tasks finishing together): they take turns on the
/// folder's .tables.lock.
int writeSweepTables(const std::string& dir);

}  // namespace tessera

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

/// Where a case stands, from its files alone (whatever ran it: this machine or a cluster).
enum class CaseState {
  Complete,     ///< its summary.json says it stopped at delta_max or by failure
  Running,      ///< a process on this machine holds its run folder's lock
  Interrupted,  ///< stopped by a signal (Ctrl-C, time limit, preemption, cancel): resumes from its checkpoint
  Failed,       ///< its run ended with an error (exit status 2 input, 3 unstable), or started and left no record
  Missing,      ///< never started
};
const char* caseStateName(CaseState state);

struct CaseStatus {
  CaseState state = CaseState::Missing;
  int exitStatus = -1;  ///< of its last run, as recorded in exit.json; -1 when none is recorded
  std::string slurmJob; ///< the Slurm job (JOB_TASK) of its last run, "" when it ran here
};
CaseStatus sweepCaseStatus(const std::string& caseDir);

/// Records how a case's run ended, for --status: case_N/exit.json {exit_status, host, slurm_job}.
void recordCaseExit(const std::string& caseDir, int exitStatus, const std::string& slurmJob);

/// The table of response parameters of every complete case in the sweep folder (sweep.csv,
/// sweep.h5); an interrupted or failed case is never tabled. Returns the number tabled. Safe to
/// call from several processes at once (cluster tasks finishing together): they take turns on the
/// folder's .tables.lock.
int writeSweepTables(const std::string& dir);

}  // namespace tessera

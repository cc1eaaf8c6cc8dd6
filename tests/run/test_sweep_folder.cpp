// The sweep folder as any runner leaves it: case states from the files alone, the Slurm batch
// script and array specification, the record of submissions, and refused Slurm settings; the
// values of --set, read whole or refused.
#include "io/folder_lock.h"
#include "io/input_error.h"
#include "io/json_text.h"
#include "run/indentation.h"
#include "run/run_summary.h"
#include "run/slurm_sweep.h"
#include "run/stop_reason.h"
#include "run/sweep.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <unistd.h>

using namespace tessera;
namespace fs = std::filesystem;

namespace {

// A whole summary.json (RunSummary's), stopped for `reason`.
std::string summaryText(StopReason reason) {
  RunSummary summary;
  summary.stopReason = reason;
  return jsonText(runSummaryJson(summary));
}

void writeText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  test::writeFile(path.string(), text);
}

}  // namespace

TEST_CASE("sweep values are read whole, a list or first:last:count, and anything else is refused") {
  REQUIRE(parseSweepAxis("E=3.3e9, 4.2e9", 1000).values == std::vector<double>{3.3e9, 4.2e9});
  REQUIRE(parseSweepAxis("mu=0.2:0.4:3", 1000).values == std::vector<double>{0.2, 0.2 + 0.2 * 1 / 2, 0.4});
  REQUIRE(parseSweepAxis("mu=0.3:0.3:1", 1000).values == std::vector<double>{0.3});
  REQUIRE(parseSweepAxis("mu=0.2", 1000).key == "material.friction");
  // Each of these used to be read as its first number, or a truncated count, and swept in silence.
  for (const std::string bad : {"radius=2.5mm,3mm", "E=4.2e9Pa", "mu=0.2:0.3", "mu=0.2:0.3:2.7", "mu=0.2;0.3",
                                "mu=0.2:0.3:3:9", "mu=1e-1x", "mu=0.2,,0.3", "mu=", "mu=abc", "mu=0.2:0.3:0", "=0.2"}) {
    INFO(bad);
    REQUIRE_THROWS_AS(parseSweepAxis(bad, 1000), InputError);
  }
  REQUIRE_THROWS_WITH(parseSweepAxis("radius=2.5mm", 1000), Catch::Contains("'2.5mm' is not a number") && Catch::Contains("SI units"));
  REQUIRE_THROWS_WITH(parseSweepAxis("mu=0.2:0.3:2.7", 1000), Catch::Contains("'2.7' is not a whole count"));
  REQUIRE_THROWS_WITH(parseSweepAxis("mu=0.1:0.5:1000000", 1000), Catch::Contains("more than --max-cases 1000"));
}

TEST_CASE("a case's state is read from its files: missing, failed, interrupted, running, complete") {
  test::TempDir folder;
  const fs::path c = folder.path() / "case_007";
  fs::create_directories(c);
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Missing);
  CHECK(sweepCaseNumber(c.string()) == 7);

  writeText(c / "log.txt", "run: ...\n");  // started by hand, no record, no checkpoint
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Failed);
  CHECK(sweepCaseStatus(c.string()).exitStatus == -1);

  {  // a runner at work: it holds the case's lock and has recorded its start
    const FolderLock lock(c.string(), "this case");
    recordCaseAttempt(c.string(), -1, "41_7");
    CHECK(folderLockHolder(c.string()) == ::getpid());
    CHECK(sweepCaseStatus(c.string()).state == CaseState::Running);
  }
  CHECK(folderLockHolder(c.string()) == 0);
  // Started here and never ended, lock free: its runner was killed before a checkpoint.
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Failed);
  CHECK(!sweepCaseStatus(c.string()).startedElsewhere);

  recordCaseAttempt(c.string(), 3, "41_7");
  const CaseStatus unstable = sweepCaseStatus(c.string());
  CHECK(unstable.state == CaseState::Failed);
  CHECK(unstable.exitStatus == 3);
  CHECK(unstable.slurmJob == "41_7");

  writeText(c / "run" / "checkpoint.h5", "");
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Failed);  // its last run's error stands
  recordCaseAttempt(c.string(), 130, "");
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Interrupted);
  recordCaseAttempt(c.string(), 128 + 15, "");  // killed by SIGTERM
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Interrupted);
  recordCaseAttempt(c.string(), 128 + 9, "");  // killed by SIGKILL (out of memory, say): not an interruption
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Failed);
  recordCaseAttempt(c.string(), -1, "");  // started, runner gone, checkpoint there: resumable
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Interrupted);

  // Started on another host and not ended: running as far as the files tell.
  writeText(c / "attempt.json", R"({"state": "started", "host": "node-that-is-not-this-one", "pid": 1, "slurm_job": "9_7"})");
  const CaseStatus elsewhere = sweepCaseStatus(c.string());
  CHECK(elsewhere.state == CaseState::Running);
  CHECK(elsewhere.startedElsewhere);
  CHECK(elsewhere.slurmJob == "9_7");
  CHECK(deadAttemptState(c.string()) == CaseState::Interrupted);

  fs::remove(c / "attempt.json");
  writeText(c / "run" / "summary.json", summaryText(StopReason::Interrupted));
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Interrupted);  // by its checkpoint
  writeText(c / "run" / "summary.json", summaryText(StopReason::Failure));
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Complete);
  writeText(c / "run" / "summary.json", summaryText(StopReason::DeltaMax));
  CHECK(sweepCaseStatus(c.string()).state == CaseState::Complete);
  // A summary cut short (or of another schema) is not a complete case, whatever its stop reason.
  writeText(c / "run" / "summary.json", R"({"stop_reason": "delta_max"})");
  CHECK_FALSE(sweepCaseComplete((c / "run").string()));
  // Complete as a run counts it (IndentationRecord::finished): stopped as its sample hook asked too;
  // not when unstable or still running, nor under a name no run writes.
  for (StopReason reason : {StopReason::Running, StopReason::DeltaMax, StopReason::Failure, StopReason::Requested,
                            StopReason::Interrupted, StopReason::Instability}) {
    INFO(stopReasonName(reason));
    REQUIRE(parseStopReason(stopReasonName(reason)) == reason);
    writeText(c / "run" / "summary.json", summaryText(reason));
    IndentationRecord record;
    record.stopReason = reason;
    CHECK(sweepCaseComplete((c / "run").string()) == record.finished());
  }
  std::string unknown = summaryText(StopReason::DeltaMax);
  unknown.replace(unknown.find("\"delta_max\""), 11, "\"finished\"");
  writeText(c / "run" / "summary.json", unknown);
  CHECK_FALSE(sweepCaseComplete((c / "run").string()));
  CHECK_FALSE(parseStopReason("finished"));
}

TEST_CASE("a sweep folder's cases are read from its manifest, a folder that is not one is refused") {
  test::TempDir folder;
  CHECK_THROWS_AS(readSweepFolder((folder.path() / "none").string()), InputError);
  CHECK_THROWS_AS(readSweepFolder(folder.path().string()), InputError);
  writeText(folder.path() / "sweep.json", R"({"keys": ["material.friction"], "cases": [
    {"directory": "case_000", "values": [0.3]}, {"directory": "case_001", "values": [0.5]}]})");
  writeText(folder.path() / "case_001" / "scene.toml", "bundle = \"slab\"\n");
  const std::vector<SweepCase> cases = readSweepFolder(folder.path().string());
  REQUIRE(cases.size() == 2);
  CHECK(cases[1].values == std::vector<double>{0.5});
  CHECK(cases[1].scene == "bundle = \"slab\"\n");
  CHECK(sweepCaseNumber(cases[1].dir) == 1);
  writeText(folder.path() / "sweep.json", R"({"keys": [], "cases": [{"directory": "results", "values": []}]})");
  CHECK_THROWS_AS(readSweepFolder(folder.path().string()), InputError);
  writeText(folder.path() / "sweep.json", "{\"keys\": [");
  CHECK_THROWS_AS(readSweepFolder(folder.path().string()), InputError);
}

TEST_CASE("the Slurm array specification joins runs of case numbers") {
  CHECK(slurmArraySpec({0, 1, 2, 3}, 0) == "0-3");
  CHECK(slurmArraySpec({10, 9, 3, 0, 1, 2, 7, 3}, 2) == "0-3,7,9-10%2");
  CHECK(slurmArraySpec({5}, 0) == "5");
}

TEST_CASE("the batch script runs one case a task and checkpoints before the time limit") {
  SlurmSettings s;
  s.partition = "compute";
  s.timeLimit = "02:00:00";
  s.cpusPerTask = 4;
  s.maxConcurrent = 8;
  s.extraOptions = {"--account=proj42"};
  const std::string script = slurmSweepScript("/scratch/E/", "/opt/tessera/bin/tessera", s, {0, 1, 2, 5});
  CHECK(script.rfind("#!/bin/bash\n", 0) == 0);
  for (const char* line : {"#SBATCH --job-name=tessera-E\n", "#SBATCH --array=0-2,5%8\n", "#SBATCH --cpus-per-task=4\n", "#SBATCH --partition=compute\n",
                           "#SBATCH --time=02:00:00\n", "#SBATCH --signal=B:TERM@120\n", "#SBATCH --requeue\n",
                           "#SBATCH --output=/scratch/E/slurm/task_%A_%a.out\n", "#SBATCH --account=proj42\n",
                           "exec '/opt/tessera/bin/tessera' sweep '/scratch/E' --case \"$SLURM_ARRAY_TASK_ID\" --threads "
                           "\"${SLURM_CPUS_PER_TASK:-4}\"\n"})
    CHECK(script.find(line) != std::string::npos);
  // Every #SBATCH line before the first command (sbatch stops reading them there).
  CHECK(script.rfind("#SBATCH") < script.find("\nexec "));
}

TEST_CASE("Slurm settings sbatch would refuse, and folders it cannot name, are refused") {
  const std::string folder = "/scratch/E";
  CHECK_NOTHROW(checkSlurmSettings({}, folder));
  for (const char* time : {"30", "5", "00:05:00", "02:00:00", "1-0", "1-12", "1-12:30:00", "UNLIMITED"})
    CHECK_NOTHROW(checkSlurmSettings({"", time, 1, 0, {}}, folder));
  for (const char* time : {"2h", "02:00:00:00", "-1", "1-", "1", "4:59", "00:04:59", "0-0:4"})
    CHECK_THROWS_AS(checkSlurmSettings({"", time, 1, 0, {}}, folder), InputError);
  CHECK_THROWS_AS(checkSlurmSettings({"a b", "", 1, 0, {}}, folder), InputError);
  CHECK_THROWS_AS(checkSlurmSettings({"", "", 0, 0, {}}, folder), InputError);
  CHECK_THROWS_AS(checkSlurmSettings({"", "", 1, -1, {}}, folder), InputError);
  CHECK_THROWS_AS(checkSlurmSettings({"", "", 1, 0, {"account=x"}}, folder), InputError);
  CHECK_THROWS_AS(checkSlurmSettings({}, "/scratch/my runs/E"), InputError);
  CHECK_THROWS_AS(checkSlurmSettings({}, "/scratch/E%1"), InputError);
}

TEST_CASE("the record of Slurm submissions keeps the settings and every job, oldest first") {
  test::TempDir folder;
  CHECK(readSlurmRecord(folder.path().string()).jobs.empty());
  fs::create_directories(folder.path() / "slurm");
  SlurmRecord record;
  record.settings = {"compute", "01:00:00", 2, 4, {"--qos=long"}};
  record.jobs = {{"41", {0, 1, 2, 3}}, {"57", {1}}};
  writeSlurmRecord(folder.path().string(), record);
  const SlurmRecord back = readSlurmRecord(folder.path().string());
  CHECK(back.settings.partition == "compute");
  CHECK(back.settings.timeLimit == "01:00:00");
  CHECK(back.settings.cpusPerTask == 2);
  CHECK(back.settings.maxConcurrent == 4);
  CHECK(back.settings.extraOptions == std::vector<std::string>{"--qos=long"});
  REQUIRE(back.jobs.size() == 2);
  CHECK(back.jobs[1].id == "57");
  CHECK(back.jobs[1].cases == std::vector<int>{1});
  writeText(folder.path() / "slurm" / "jobs.json", "{\"jobs\": 3}");
  CHECK_THROWS_AS(readSlurmRecord(folder.path().string()), InputError);
}

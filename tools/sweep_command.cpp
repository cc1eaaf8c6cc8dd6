// tessera sweep: a scene run over a list (or grid) of parameter values, cases in parallel on this
// machine or as a Slurm job array; --status, --resubmit and --case on a sweep folder;
// tessera report: the paper's figures from a sweep.
#include "io/folder_lock.h"
#include "io/json_text.h"
#include "io/input_error.h"
#include "io/output_directory.h"
#include "io/safe_write.h"
#include "run/slurm_sweep.h"
#include "solver/solver_settings.h"
#include "run/sweep.h"
#include "tools/child_process.h"
#include "tools/commands.h"
#include "tools/plot_scripts.h"
#include "tools/slurm_queue.h"
#include "tools/sweep_runner.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <thread>

namespace tessera::tools {

namespace fs = std::filesystem;

namespace {

struct SweepArguments {
  std::string target;  // the base scene; with --status, --resubmit, --case: the sweep folder
  std::string output;
  std::string preset;  // applied to every case
  std::vector<std::string> sets;
  int jobs = 0;     // 0: one per core
  int threads = 1;  // per case
  bool zip = false; // axes varied together, not as a grid
  bool extend = false;  // add cases of new values to an existing sweep folder
  long maxCases = 1000;
  // Slurm
  bool slurm = false, dryRun = false;
  SlurmSettings settings;
  struct {
    bool partition = false, time = false, cpusPerTask = false, maxConcurrent = false, sbatch = false;
  } given;  // the Slurm settings given on this command line
  // On a sweep folder
  bool status = false, json = false, resubmit = false;
  int caseNumber = -1;
};

// Where a case stands: its files, and Slurm's word while Slurm still runs it.
struct CaseReport {
  const SweepCase* sweepCase;
  CaseStatus files;
  CaseState state = CaseState::Missing;  // from the files, or Queued, Running or Unknown from Slurm
  std::string slurmJob;    // JOB_TASK of its latest submission or attempt, "" if none
  std::string slurmState;  // squeue's state of that task, "" when Slurm no longer knows it
  bool submitted = false;  // slurmJob is a submission recorded in DIR/slurm/jobs.json
};

std::vector<CaseReport> reportCases(const std::vector<SweepCase>& cases, const SlurmRecord& record,
                                    std::string* slurmProblem) {
  std::vector<CaseReport> reports;
  bool slurmJobs = !record.jobs.empty();
  for (const SweepCase& c : cases) {
    CaseReport r{&c, sweepCaseStatus(c.dir), CaseState::Missing, "", "", false};
    r.slurmJob = r.files.slurmJob;  // a task submitted by hand records its job when it starts
    const int number = sweepCaseNumber(c.dir);
    for (const SlurmJob& job : record.jobs)  // the latest submission of the case
      if (std::find(job.cases.begin(), job.cases.end(), number) != job.cases.end()) {
        r.slurmJob = job.id + "_" + std::to_string(number);
        r.submitted = true;
      }
    slurmJobs = slurmJobs || !r.slurmJob.empty();
    reports.push_back(r);
  }
  SlurmTaskStates queue;
  if (slurmJobs) {
    queue = querySlurmTasks();
    if (slurmProblem && !queue.available) *slurmProblem = queue.problem;
  }
  for (CaseReport& r : reports) {
    r.state = r.files.state;
    if (r.files.state == CaseState::Complete || r.slurmJob.empty()) continue;
    const std::size_t split = r.slurmJob.find('_');
    const auto found = queue.state.find({r.slurmJob.substr(0, split), std::stoi(r.slurmJob.substr(split + 1))});
    if (found != queue.state.end()) r.slurmState = found->second;
    const std::optional<CaseState> phase = slurmTaskPhase(r.slurmState);
    if (!queue.available) {
      if (r.submitted && r.files.state != CaseState::Running) r.state = CaseState::Unknown;  // Slurm may hold it queued or running
    } else if (phase) {
      r.state = *phase;
    } else if (r.files.startedElsewhere) {
      r.state = deadAttemptState(r.sweepCase->dir);  // its task is over: its runner was killed
    }
  }
  return reports;
}

// The cases not left to another runner: neither queued nor running (here or on Slurm), nor of a
// state Slurm cannot tell now; with `skipComplete`, not complete either.
std::vector<const SweepCase*> casesToRun(const std::vector<CaseReport>& reports, bool skipComplete = true) {
  std::vector<const SweepCase*> pending;
  for (const CaseReport& r : reports)
    if ((r.state != CaseState::Complete || !skipComplete) && r.state != CaseState::Running && r.state != CaseState::Queued &&
        r.state != CaseState::Unknown)
      pending.push_back(r.sweepCase);
  return pending;
}

// Refuses to start cases while Slurm cannot say which of the folder's cases it still holds.
void requireKnownStates(const std::vector<CaseReport>& reports, const std::string& problem) {
  const auto unknown = std::count_if(reports.begin(), reports.end(), [](const CaseReport& r) { return r.state == CaseState::Unknown; });
  if (unknown > 0)
    throw InputError("Slurm cannot say whether " + std::to_string(unknown) + " case(s) of this sweep are still queued or "
                     "running (" + problem + "); run this where squeue answers, so that no case runs twice (or, "
                     "when none of its jobs can run any more, remove its slurm/jobs.json)");
}

std::string valuesText(const std::vector<std::string>& keys, const std::vector<double>& values) {
  std::string text;
  for (std::size_t k = 0; k < keys.size() && k < values.size(); ++k) {
    char v[32];
    std::snprintf(v, sizeof v, "%g", values[k]);
    text += (k ? ", " : "") + keys[k] + " = " + v;
  }
  return text;
}

std::vector<std::string> sweepKeys(const std::string& folder) {
  std::ifstream in(fs::path(folder) / "sweep.json");
  return nlohmann::json::parse(in).at("keys").get<std::vector<std::string>>();
}

// Writes the batch script for the cases (numbers) and submits it, unless a dry run.
void submitToSlurm(const std::string& folder, const SlurmSettings& settings, const std::vector<int>& numbers, bool dryRun) {
  const std::string dir = fs::absolute(folder).lexically_normal().string();
  checkSlurmSettings(settings, dir);
  const std::string script = slurmSweepScript(dir, selfExecutable(), settings, numbers);
  const fs::path scriptPath = fs::path(dir) / "slurm" / "sweep.sbatch";
  fs::create_directories(scriptPath.parent_path());
  writeTextFileSafely(scriptPath, script);
  SlurmRecord record = readSlurmRecord(dir);
  record.settings = settings;  // kept with the script, so that --resubmit submits it as written
  writeSlurmRecord(dir, record);
  if (dryRun) {
    std::printf("%s", script.c_str());
    std::printf("# written to %s (dry run: nothing submitted); submit it with: sbatch %s\n", scriptPath.c_str(),
                scriptPath.c_str());
    return;
  }
  const std::string id = submitSlurmArray(scriptPath.string(), slurmArraySpec(numbers, settings.maxConcurrent), {});
  record.jobs.push_back({id, numbers});
  writeSlurmRecord(dir, record);
  std::printf("sweep: submitted %zu case(s) of %s as Slurm job %s (array %s)\n"
              "follow it with: tessera sweep %s --status\n",
              numbers.size(), folder.c_str(), id.c_str(), slurmArraySpec(numbers, settings.maxConcurrent).c_str(),
              folder.c_str());
}

std::vector<int> caseNumbers(const std::vector<const SweepCase*>& cases) {
  std::vector<int> numbers;
  for (const SweepCase* c : cases) numbers.push_back(sweepCaseNumber(c->dir));
  return numbers;
}

SlurmSettings settingsOver(SlurmSettings base, const SweepArguments& a) {
  if (a.given.partition) base.partition = a.settings.partition;
  if (a.given.time) base.timeLimit = a.settings.timeLimit;
  if (a.given.cpusPerTask) base.cpusPerTask = a.settings.cpusPerTask;
  if (a.given.maxConcurrent) base.maxConcurrent = a.settings.maxConcurrent;
  if (a.given.sbatch) base.extraOptions = a.settings.extraOptions;
  return base;
}

void printFinish(const std::string& folder, int status) {
  const int complete = writeSweepTables(folder);
  std::printf("sweep: %d of %zu cases in %s complete; table %s (and sweep.h5)\n", complete, readSweepFolder(folder).size(),
              folder.c_str(), (fs::path(folder) / "sweep.csv").c_str());
  if (status == 130) std::printf("sweep: stopped; run the same command again (or --resubmit) to finish it\n");
  else std::printf("draw the figures with: tessera report %s\n", folder.c_str());
}

// --dry-run without --slurm: the command of each case to run, one a line, for any launcher
// (GNU parallel, xargs -P, another scheduler's array, an MPI launcher's ranks).
void printJobList(const std::string& folder, const std::vector<const SweepCase*>& cases, int threads) {
  const std::string self = selfExecutable(), dir = fs::absolute(folder).lexically_normal().string();
  for (const SweepCase* c : cases)
    std::printf("%s sweep %s --case %d --threads %d\n", self.c_str(), dir.c_str(), sweepCaseNumber(c->dir), threads);
  std::fprintf(stderr, "sweep: %zu case(s) to run in %s (dry run: nothing started); each line above runs one, anywhere "
               "the folder is reachable\n", cases.size(), folder.c_str());
}

int jobsFor(const SweepArguments& a) {
  if (a.jobs < 0 || a.jobs > 256) throw InputError("--jobs must be 0 (cores / threads) to 256, got " + std::to_string(a.jobs));
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, cores / static_cast<unsigned>(a.threads)));
}

// tessera sweep SCENE -o DIR --set ... [--slurm]
int newSweep(const SweepArguments& a) {
  if (a.output.empty()) throw InputError("give the sweep folder with -o DIR");
  if (a.sets.empty()) throw InputError("give at least one --set KEY=values (e.g. --set E=3.3e9,4.2e9)");
  if (a.maxCases < 1) throw InputError("--max-cases must be at least 1");
  if (a.slurm && a.jobs != 0)
    throw InputError("--jobs is for a sweep run here; with --slurm, limit the cases running at once with --max-concurrent");
  SweepPlan plan{a.target, a.preset, {}, a.zip, a.maxCases};
  for (const auto& s : a.sets) plan.axes.push_back(parseSweepAxis(s, a.maxCases));
  std::vector<SweepCase> cases = sweepCases(plan);  // all checked before anything is made
  SlurmSettings settings = a.settings;
  if (!a.given.cpusPerTask) settings.cpusPerTask = a.threads;
  if (a.slurm) checkSlurmSettings(settings, fs::absolute(a.output).lexically_normal().string());
  const int jobs = a.slurm ? 1 : jobsFor(a);

  requireWritableDirectory(a.output);
  const FolderLock lock(a.output, "a sweep");
  cases = placeSweepCases(a.output, plan, cases, a.extend);
  std::string problem;
  const std::vector<CaseReport> reports = reportCases(cases, readSlurmRecord(a.output), &problem);
  requireKnownStates(reports, problem);
  if (a.slurm || a.dryRun) {
    const std::vector<const SweepCase*> pending = casesToRun(reports);
    if (!a.slurm) {
      printJobList(a.output, pending, a.threads);
      return 0;
    }
    const std::vector<int> numbers = caseNumbers(pending);
    if (numbers.empty()) {
      std::printf("sweep: every case of %s is complete, queued or running; nothing to submit\n", a.output.c_str());
      return 0;
    }
    submitToSlurm(a.output, settings, numbers, a.dryRun);
    return 0;
  }
  std::vector<SweepCase> here;  // all but those queued or running elsewhere (complete ones are reported as such)
  for (const SweepCase* c : casesToRun(reports, false)) here.push_back(*c);
  if (here.size() < cases.size())
    std::fprintf(stderr, "sweep: %zu case(s) queued or running elsewhere (Slurm or another process) left to it\n",
                 cases.size() - here.size());
  const int status = runSweepCases(here, jobs, a.threads, "");
  printFinish(a.output, status);
  return status;
}

// tessera sweep DIR --case N: one case, as a Slurm array task runs it.
int runOneCase(const SweepArguments& a) {
  const std::vector<SweepCase> cases = readSweepFolder(a.target);
  for (const SweepCase& c : cases) {
    if (sweepCaseNumber(c.dir) != a.caseNumber) continue;
    const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
    const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
    const std::string slurmJob = job && task ? std::string(job) + "_" + task : "";
    const int status = runSweepCases({c}, 1, a.threads, slurmJob);
    try {
      writeSweepTables(a.target);
    } catch (const std::exception& e) {  // the case's own result stands; the next writer tables it
      std::fprintf(stderr, "sweep: warning: the tables were not rewritten: %s\n", e.what());
    }
    return status;
  }
  throw InputError(a.target + ": has no case_" + std::to_string(a.caseNumber) + " (sweep.json lists " +
                   std::to_string(cases.size()) + " cases); give the number of one of its case folders");
}

// tessera sweep DIR --status [--json]
int printStatus(const SweepArguments& a) {
  const std::vector<SweepCase> cases = readSweepFolder(a.target);
  std::string slurmProblem;
  const SlurmRecord record = readSlurmRecord(a.target);
  const std::vector<CaseReport> reports = reportCases(cases, record, &slurmProblem);
  std::map<std::string, int> counts{{"complete", 0}, {"queued", 0},  {"running", 0}, {"interrupted", 0},
                                    {"failed", 0},   {"missing", 0}, {"unknown", 0}};
  for (const CaseReport& r : reports) ++counts[caseStateName(r.state)];
  const std::vector<std::string> keys = sweepKeys(a.target);
  if (a.json) {
    nlohmann::json j = {{"folder", a.target}, {"counts", counts}, {"cases", nlohmann::json::array()},
                        {"slurm_jobs", nlohmann::json::array()}};
    for (const SlurmJob& job : record.jobs) j["slurm_jobs"].push_back(job.id);
    if (!slurmProblem.empty()) j["slurm_problem"] = slurmProblem;
    for (const CaseReport& r : reports)
      j["cases"].push_back({{"case", fs::path(r.sweepCase->dir).filename().string()},
                            {"state", caseStateName(r.state)},
                            {"values", r.sweepCase->values},
                            {"exit_status", r.files.exitStatus >= 0 ? nlohmann::json(r.files.exitStatus) : nlohmann::json()},
                            {"slurm_job", r.slurmJob},
                            {"slurm_state", r.slurmState}});
    std::fputs(jsonText(j).c_str(), stdout);
    return 0;
  }
  std::printf("sweep %s: %zu cases: %d complete, %d queued, %d running, %d interrupted, %d failed, %d missing%s\n",
              a.target.c_str(), cases.size(), counts["complete"], counts["queued"], counts["running"], counts["interrupted"],
              counts["failed"], counts["missing"],
              counts["unknown"] ? (", " + std::to_string(counts["unknown"]) + " unknown").c_str() : "");
  if (!slurmProblem.empty()) std::printf("(Slurm's state not available: %s; the case files tell the rest)\n", slurmProblem.c_str());
  for (const CaseReport& r : reports) {
    std::string detail;
    if (!r.slurmJob.empty()) detail = "slurm " + r.slurmJob + (r.slurmState.empty() ? "" : " " + r.slurmState);
    if (r.state == CaseState::Failed)
      detail += std::string(detail.empty() ? "" : ", ") +
                (r.files.exitStatus > 0 ? "exit " + std::to_string(r.files.exitStatus) +
                                              (r.files.exitStatus == 2 ? " (bad input)" : r.files.exitStatus == 3 ? " (unstable)" : "")
                                        : std::string("no exit recorded")) +
                ", see " + (fs::path(r.sweepCase->dir).filename() / "log.txt").string();
    std::printf("  %-10s %-12s %-34s %s\n", fs::path(r.sweepCase->dir).filename().c_str(), caseStateName(r.state), detail.c_str(),
                valuesText(keys, r.sweepCase->values).c_str());
  }
  if (counts["interrupted"] + counts["failed"] + counts["missing"] > 0)
    std::printf("run the missing, failed and interrupted cases with: tessera sweep %s --resubmit\n", a.target.c_str());
  return 0;
}

// tessera sweep DIR --resubmit: the cases neither complete nor running, through Slurm when the
// sweep was submitted there, else here.
int resubmit(const SweepArguments& a) {
  const std::vector<SweepCase> cases = readSweepFolder(a.target);
  const SlurmRecord record = readSlurmRecord(a.target);
  const bool slurm = a.slurm || fs::exists(fs::path(a.target) / "slurm" / "jobs.json");
  const FolderLock lock(a.target, "a sweep");
  std::string problem;
  const std::vector<CaseReport> reports = reportCases(cases, record, &problem);
  requireKnownStates(reports, problem);
  const std::vector<const SweepCase*> pending = casesToRun(reports);
  if (pending.empty()) {
    std::printf("sweep: every case of %s is complete, queued or running; nothing to resubmit\n", a.target.c_str());
    writeSweepTables(a.target);
    return 0;
  }
  if (slurm) {
    const bool recorded = fs::exists(fs::path(a.target) / "slurm" / "jobs.json");
    SlurmSettings base = recorded ? record.settings : SlurmSettings{};
    if (!recorded && !a.given.cpusPerTask) base.cpusPerTask = a.threads;
    submitToSlurm(a.target, settingsOver(base, a), caseNumbers(pending), a.dryRun);
    return 0;
  }
  if (a.dryRun) {
    printJobList(a.target, pending, a.threads);
    return 0;
  }
  std::vector<SweepCase> run;
  for (const SweepCase* c : pending) run.push_back(*c);
  const int status = runSweepCases(run, jobsFor(a), a.threads, "");
  printFinish(a.target, status);
  return status;
}

int runSweep(const SweepArguments& a) {
  if (a.threads < 1 || a.threads > kMaxThreads)
    throw InputError("--threads must be 1 to " + std::to_string(kMaxThreads) + " per case, got " + std::to_string(a.threads));
  const int modes = (a.status ? 1 : 0) + (a.resubmit ? 1 : 0) + (a.caseNumber >= 0 ? 1 : 0);
  if (modes > 1) throw InputError("give one of --status, --resubmit, --case");
  if (a.json && !a.status) throw InputError("--json goes with --status: tessera sweep DIR --status --json");
  if (modes == 1 && (!a.sets.empty() || !a.output.empty()))
    throw InputError("--status, --resubmit and --case take the sweep folder in place of the scene, without -o or --set: "
                     "tessera sweep DIR --status");
  if (a.status) return printStatus(a);
  if (a.resubmit) return resubmit(a);
  if (a.caseNumber >= 0) return runOneCase(a);
  return newSweep(a);
}

}  // namespace

void addSweepCommand(CLI::App& app) {
  auto args = std::make_shared<SweepArguments>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run a scene over parameter values (a list, a range, or a grid of two), cases in parallel here or as a Slurm job array.");
  cmd->add_option("scene", args->target, "Base scene file (TOML); with --status, --resubmit or --case: the sweep folder")->required();
  cmd->add_option("-o,--output", args->output, "Sweep directory: case_NNN/ (scene.toml, run/, log.txt, attempt.json), sweep.json, sweep.csv");
  cmd->add_option("--set", args->sets,
                  "KEY=v1,v2,... or KEY=first:last:count, SI units; KEY is table.key of the scene or E, mu, speed, radius, "
                  "density; repeat for a grid");
  cmd->add_flag("--zip", args->zip,
               "Vary the --set keys together (the k-th value of each in case k; equal counts) instead of as a grid");
  cmd->add_option("--preset", args->preset, "Speed/accuracy setting applied to every case (as in tessera run --preset)");
  cmd->add_option("--jobs", args->jobs, "Cases run at once here [default: cores / threads]");
  cmd->add_option("--threads", args->threads, "Threads per case")->capture_default_str();
  cmd->add_flag("--extend", args->extend, "Add cases of new values to the sweep already in -o (same keys, scene and preset)");
  cmd->add_option("--max-cases", args->maxCases, "Refuse a sweep of more cases than this")->capture_default_str();

  const std::string slurmGroup = "Slurm (docs/cluster.md)";
  cmd->add_flag("--slurm", args->slurm, "Submit the cases as a Slurm job array (sbatch) instead of running them here")->group(slurmGroup);
  cmd->add_option("--partition", args->settings.partition, "Slurm partition")->group(slurmGroup)
      ->each([args](const std::string&) { args->given.partition = true; });
  cmd->add_option("--time", args->settings.timeLimit, "Time limit per case, HH:MM:SS (a case checkpoints 2 min before it)")
      ->group(slurmGroup)->each([args](const std::string&) { args->given.time = true; });
  cmd->add_option("--cpus-per-task", args->settings.cpusPerTask, "Cores per case, also its threads [default: --threads]")
      ->group(slurmGroup)->each([args](const std::string&) { args->given.cpusPerTask = true; });
  cmd->add_option("--max-concurrent", args->settings.maxConcurrent, "Cases running at once on the cluster [default: no limit]")
      ->group(slurmGroup)->each([args](const std::string&) { args->given.maxConcurrent = true; });
  cmd->add_option("--sbatch", args->settings.extraOptions, "A further sbatch option, e.g. --sbatch=--account=proj42 (repeat)")
      ->group(slurmGroup)->allow_extra_args(false)->each([args](const std::string&) { args->given.sbatch = true; });
  cmd->add_flag("--dry-run", args->dryRun,
                "Write the sweep folder and run nothing: with --slurm, write DIR/slurm/sweep.sbatch and print it; without, "
                "print the command of each case to run (a job list for any launcher)")
      ->group(slurmGroup);

  const std::string folderGroup = "On a sweep folder (in place of the scene)";
  cmd->add_flag("--status", args->status, "Where each case stands: complete, queued, running, interrupted, failed, missing")
      ->group(folderGroup);
  cmd->add_flag("--json", args->json, "With --status: as JSON")->group(folderGroup);
  cmd->add_flag("--resubmit", args->resubmit,
                "Run the missing, failed and interrupted cases again (interrupted ones resume): through Slurm if the sweep "
                "was submitted there, else here")
      ->group(folderGroup);
  cmd->add_option("--case", args->caseNumber, "Run case_N alone (what each Slurm array task runs)")->group(folderGroup);
  cmd->footer("Example (the paper's E study): tessera sweep assets/scenes/default.toml -o out/E \\\n"
              "  --set E=3.3e9,4.2e9,5e9,7.5e9,10e9,20e9,30e9,50e9,75e9\n"
              "On a cluster: the same with --slurm --time 01:00:00; then tessera sweep out/E --status.\n"
              "Re-running a sweep finishes only the missing cases (and resumes stopped ones); Ctrl-C stops\n"
              "it (running cases checkpoint; exit status 130). Exit status: 0 all done (or submitted),\n"
              "2 bad input or a case's bad input, 3 a case became unstable, 130 interrupted.");
  cmd->callback([args] {
    if (const int status = runSweep(*args)) throw CLI::RuntimeError(status);
  });

  auto report = std::make_shared<std::pair<std::string, std::string>>();
  CLI::App* rep = app.add_subcommand("report", "Draw the paper's figures (PNG and SVG) from a sweep directory.");
  rep->add_option("sweep", report->first, "Sweep directory")->required();
  rep->add_option("--experiments", report->second,
                  "CSV of experimental points (label, E_Pa, L_m, h_m, P_peak_N, delta_peak_m) for the normalised plot");
  rep->callback([report] {
    if (!fs::exists(fs::path(report->first) / "sweep.json"))
      throw InputError(report->first + ": not a sweep folder (no sweep.json); give the -o folder of tessera sweep");
    try {
      writeSweepTables(report->first);  // from the case folders as they stand, whatever ran them
    } catch (const std::exception& e) {  // a folder shared read-only: its tables as they are
      std::fprintf(stderr, "report: warning: drawing sweep.csv as it is (not rewritten: %s)\n", e.what());
    }
    std::vector<std::string> arguments{report->first};
    if (!report->second.empty()) arguments.insert(arguments.end(), {"--experiments", report->second});
    const int status = runPlotScript("report_sweep.py", arguments, "");
    if (status == 127)
      throw InputError("report: report_sweep.py or python3 not found beside tessera; reinstall, or set TESSERA_PYTHON");
    if (status != 0) throw CLI::RuntimeError(2);  // the script printed why
  });
}

}  // namespace tessera::tools

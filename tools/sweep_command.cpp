// tessera sweep: a scene run over a list (or grid) of parameter values, cases in parallel;
// tessera report: the paper's figures from a sweep.
#include "io/input_error.h"
#include "run/sweep.h"
#include "tools/child_process.h"
#include "tools/commands.h"
#include "tools/plot_scripts.h"
#include "io/folder_lock.h"
#include "io/output_directory.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

namespace tessera::tools {

namespace fs = std::filesystem;

namespace {

struct SweepArguments {
  std::string scene, output;
  std::string preset;  // applied to every case
  std::vector<std::string> sets;
  int jobs = 0;     // 0: one per core
  int threads = 1;  // per case
  bool zip = false; // axes varied together, not as a grid
  bool extend = false;  // add cases of new values to an existing sweep folder
  long maxCases = 1000;
};

// The running cases, for the signal handler: it stops launching and passes the signal on.
constexpr int kMaxJobs = 256;
std::atomic<bool> sweepStopRequested{false};
std::atomic<pid_t> runningCase[kMaxJobs];
extern "C" void stopSweep(int signal) {
  sweepStopRequested = true;
  for (auto& pid : runningCase)
    if (const pid_t p = pid.load(); p > 0) ::kill(p, signal);  // async-signal-safe
}

// Runs the cases, `jobs` at a time, each an ordinary `tessera run` (resumed where a checkpoint
// is). Returns the exit status of the sweep: 130 when stopped by a signal, else the first
// failed case's (2 input, 3 unstable), else 0.
int runCases(const std::vector<SweepCase>& cases, int jobs, int threads) {
  const std::string self = selfExecutable();
  std::atomic<std::size_t> next{0};
  std::atomic<int> failure{0};
  std::mutex print;
  const auto worker = [&](int slot) {
    for (std::size_t c; !sweepStopRequested && (c = next++) < cases.size();) {
      const fs::path dir(cases[c].dir), run = dir / "run";
      const std::string name = dir.filename().string();
      if (sweepCaseComplete(run.string())) {
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "sweep: %s already complete\n", name.c_str());
        continue;
      }
      const bool resume = fs::exists(run / "checkpoint.h5");
      std::vector<std::string> command{self, "run"};
      if (resume) command.insert(command.end(), {"--resume", run.string()});
      else command.insert(command.end(), {(dir / "scene.toml").string(), "-o", run.string()});
      command.insert(command.end(), {"--no-plot", "--threads", std::to_string(threads)});
      {
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "sweep: %s %s\n", resume ? "resuming" : "running", name.c_str());
      }
      const pid_t pid = startProcess(command, (dir / "log.txt").string());
      runningCase[slot] = pid;
      if (sweepStopRequested) ::kill(pid, SIGINT);  // the signal came between the check and the start
      const int status = waitProcess(pid);
      runningCase[slot] = 0;
      std::lock_guard<std::mutex> lock(print);
      if (status == 0) {
        std::fprintf(stderr, "sweep: %s done\n", name.c_str());
      } else if (status == 130 || sweepStopRequested) {
        std::fprintf(stderr, "sweep: %s interrupted (incomplete; the next sweep resumes it)\n", name.c_str());
      } else {
        int none = 0;
        failure.compare_exchange_strong(none, status == 2 || status == 3 ? status : 1);
        std::fprintf(stderr, "sweep: %s stopped with status %d (see %s)\n", name.c_str(), status,
                     (dir / "log.txt").c_str());
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker, j);
  for (auto& t : pool) t.join();
  return sweepStopRequested ? 130 : failure.load();
}

int runSweep(const SweepArguments& a) {
  if (a.threads < 1) throw InputError("--threads must be at least 1 per case, got " + std::to_string(a.threads));
  if (a.jobs < 0 || a.jobs > kMaxJobs)
    throw InputError("--jobs must be 0 (cores / threads) to " + std::to_string(kMaxJobs) + ", got " + std::to_string(a.jobs));
  if (a.maxCases < 1) throw InputError("--max-cases must be at least 1");
  SweepPlan plan{a.scene, a.preset, {}, a.zip, a.maxCases};
  for (const auto& s : a.sets) plan.axes.push_back(parseSweepAxis(s, a.maxCases));
  std::vector<SweepCase> cases = sweepCases(plan);  // all checked before anything is made

  requireWritableDirectory(a.output);
  const FolderLock lock(a.output, "a sweep");
  cases = placeSweepCases(a.output, plan, cases, a.extend);

  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, cores / static_cast<unsigned>(a.threads)));
  std::signal(SIGINT, stopSweep);
  std::signal(SIGTERM, stopSweep);
  const int status = runCases(cases, std::min<int>(jobs, static_cast<int>(cases.size())), a.threads);
  const int complete = writeSweepTables(a.output);
  std::ifstream manifest(fs::path(a.output) / "sweep.json");
  const std::size_t total = nlohmann::json::parse(manifest)["cases"].size();
  std::printf("sweep: %d of %zu cases in %s complete; table %s (and sweep.h5)\n", complete, total, a.output.c_str(),
              (fs::path(a.output) / "sweep.csv").c_str());
  if (status == 130) std::printf("sweep: stopped; run the same command again to finish it\n");
  else std::printf("draw the figures with: tessera report %s\n", a.output.c_str());
  return status;
}

}  // namespace

void addSweepCommand(CLI::App& app) {
  auto args = std::make_shared<SweepArguments>();
  CLI::App* cmd = app.add_subcommand("sweep", "Run a scene over parameter values (a list, a range, or a grid of two), cases in parallel.");
  cmd->add_option("scene", args->scene, "Base scene file (TOML)")->required();
  cmd->add_option("-o,--output", args->output, "Sweep directory: case_NNN/ (scene.toml, run/), sweep.json, sweep.csv")->required();
  cmd->add_option("--set", args->sets,
                  "KEY=v1,v2,... or KEY=first:last:count, SI units; KEY is table.key of the scene or E, mu, speed, radius, "
                  "density; repeat for a grid")
      ->required();
  cmd->add_flag("--zip", args->zip,
               "Vary the --set keys together (the k-th value of each in case k; equal counts) instead of as a grid");
  cmd->add_option("--preset", args->preset, "Speed/accuracy setting applied to every case (as in tessera run --preset)");
  cmd->add_option("--jobs", args->jobs, "Cases run at once [default: cores / threads]");
  cmd->add_option("--threads", args->threads, "Threads per case")->capture_default_str();
  cmd->add_flag("--extend", args->extend, "Add cases of new values to the sweep already in -o (same keys, scene and preset)");
  cmd->add_option("--max-cases", args->maxCases, "Refuse a sweep of more cases than this")->capture_default_str();
  cmd->footer("Example (the paper's E study): tessera sweep assets/scenes/default.toml -o out/E \\\n"
              "  --set E=3.3e9,4.2e9,5e9,7.5e9,10e9,20e9,30e9,50e9,75e9\n"
              "Re-running a sweep finishes only the missing cases (and resumes stopped ones); Ctrl-C stops\n"
              "it (running cases checkpoint; exit status 130). Exit status: 0 all done, 2 or 3 a case's error.");
  cmd->callback([args] {
    if (const int status = runSweep(*args)) throw CLI::RuntimeError(status);
  });

  auto report = std::make_shared<std::pair<std::string, std::string>>();
  CLI::App* rep = app.add_subcommand("report", "Draw the paper's figures (PNG and SVG) from a sweep directory.");
  rep->add_option("sweep", report->first, "Sweep directory")->required();
  rep->add_option("--experiments", report->second,
                  "CSV of experimental points (label, E_Pa, L_m, h_m, P_peak_N, delta_peak_m) for the normalised plot");
  rep->callback([report] {
    if (!fs::exists(fs::path(report->first) / "sweep.csv"))
      throw InputError(report->first + ": not a sweep folder (no sweep.csv); give the -o folder of tessera sweep");
    std::vector<std::string> arguments{report->first};
    if (!report->second.empty()) arguments.insert(arguments.end(), {"--experiments", report->second});
    const int status = runPlotScript("report_sweep.py", arguments, "");
    if (status == 127)
      throw InputError("report: report_sweep.py or python3 not found beside tessera; reinstall, or set TESSERA_PYTHON");
    if (status != 0) throw CLI::RuntimeError(2);  // the script printed why
  });
}

}  // namespace tessera::tools

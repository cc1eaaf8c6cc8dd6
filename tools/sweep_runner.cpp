#include "tools/sweep_runner.h"

#include "io/folder_lock.h"
#include "io/input_error.h"
#include "tools/child_process.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <exception>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>
#include <unistd.h>

namespace tessera::tools {

namespace fs = std::filesystem;

namespace {

// The running cases, for the signal handler: it stops launching and passes the signal on.
constexpr int kMaxJobs = 256;
std::atomic<bool> sweepStopRequested{false};
std::atomic<pid_t> runningCase[kMaxJobs];
extern "C" void stopSweep(int signal) {
  sweepStopRequested = true;
  for (auto& pid : runningCase)
    if (const pid_t p = pid.load(); p > 0) ::kill(p, signal);  // async-signal-safe
}

}  // namespace

int runSweepCases(const std::vector<SweepCase>& cases, int jobs, int threads, const std::string& slurmJob) {
  jobs = std::max(1, std::min({jobs, kMaxJobs, static_cast<int>(cases.size())}));
  std::signal(SIGINT, stopSweep);
  std::signal(SIGTERM, stopSweep);
  const std::string self = selfExecutable();
  std::atomic<std::size_t> next{0};
  std::atomic<int> failure{0};
  std::mutex print;
  // An error in a worker (a case's attempt record that cannot be written: a full disk) stops
  // new cases and is raised here after the running ones end: a thread may not let it escape.
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  const auto runCase = [&](int slot, std::size_t c) {
    const fs::path dir(cases[c].dir), run = dir / "run";
    const std::string name = dir.filename().string();
    if (sweepCaseComplete(run.string())) {
      std::lock_guard<std::mutex> lock(print);
      std::fprintf(stderr, "sweep: %s already complete\n", name.c_str());
      return;
    }
    // The case's own lock for the whole attempt: one runner a case, whatever started them.
    std::unique_ptr<FolderLock> caseLock;
    try {
      caseLock = std::make_unique<FolderLock>(dir.string(), "this case");
    } catch (const InputError&) {
      std::lock_guard<std::mutex> lock(print);
      std::fprintf(stderr, "sweep: %s is running in another process; left to it\n", name.c_str());
      return;
    }
    recordCaseAttempt(dir.string(), -1, slurmJob);
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
    recordCaseAttempt(dir.string(), status, slurmJob);
    caseLock.reset();
    std::lock_guard<std::mutex> lock(print);
    if (status == 0) {
      std::fprintf(stderr, "sweep: %s done\n", name.c_str());
    } else if (status == 130 || sweepStopRequested) {
      std::fprintf(stderr, "sweep: %s interrupted (incomplete; it resumes from its checkpoint when run again)\n", name.c_str());
    } else {
      int none = 0;
      failure.compare_exchange_strong(none, status == 2 || status == 3 ? status : 1);
      std::fprintf(stderr, "sweep: %s stopped with status %d (see %s)\n", name.c_str(), status,
                   (dir / "log.txt").c_str());
    }
  };
  const auto worker = [&](int slot) {
    for (std::size_t c; !sweepStopRequested && !failed && (c = next++) < cases.size();) {
      try {
        runCase(slot, c);
      } catch (...) {
        std::lock_guard<std::mutex> lock(print);
        if (!failed.exchange(true)) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker, j);
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return sweepStopRequested ? 130 : failure.load();
}

}  // namespace tessera::tools

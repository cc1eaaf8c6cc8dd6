// tessera sweep: a scene run over a list (or grid) of parameter values, cases in parallel;
// tessera report: the paper's figures from a sweep.
#include "io/file_digest.h"
#include "io/input_error.h"
#include "io/safe_write.h"
#include "run/presets.h"
#include "run/run_output.h"
#include "run/scene.h"
#include "tools/child_process.h"
#include "tools/commands.h"
#include "tools/plot_scripts.h"
#include "io/folder_lock.h"
#include "io/output_directory.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

namespace tessera::tools {

namespace fs = std::filesystem;

namespace {

// Short names for the keys swept most.
const std::map<std::string, std::string> kAliases{
    {"E", "material.youngs_modulus"}, {"mu", "material.friction"}, {"speed", "indenter.speed"},
    {"radius", "indenter.radius"}, {"density", "material.density"}};

std::string formatValue(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

struct Axis {
  std::string key;  // table.key
  std::vector<double> values;
};

// "KEY=v1,v2,..." or "KEY=first:last:count" (count values evenly spaced, ends included).
Axis parseAxis(const std::string& text, long maxCases) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError("--set '" + text + "': give KEY=v1,v2,... or KEY=first:last:count");
  Axis axis;
  axis.key = text.substr(0, eq);
  if (kAliases.count(axis.key)) axis.key = kAliases.at(axis.key);
  const std::string values = text.substr(eq + 1);
  try {
    if (std::count(values.begin(), values.end(), ':') == 2) {
      std::stringstream in(values);
      std::string a, b, n;
      std::getline(in, a, ':');
      std::getline(in, b, ':');
      std::getline(in, n);
      const double first = std::stod(a), last = std::stod(b);
      const long count = std::stol(n);
      if (count < 1) throw std::invalid_argument("count");
      if (count > maxCases)
        throw InputError("--set '" + text + "': " + std::to_string(count) + " values, more than --max-cases " +
                         std::to_string(maxCases) + "; give fewer, or raise --max-cases if you mean it");
      for (int k = 0; k < count; ++k) axis.values.push_back(count == 1 ? first : first + (last - first) * k / (count - 1));
    } else {
      std::stringstream in(values);
      std::string v;
      while (std::getline(in, v, ',')) axis.values.push_back(std::stod(v));
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception&) {
    throw InputError("--set '" + text + "': values must be numbers (SI units), e.g. E=3.3e9,4.2e9 or mu=0.2:1:5");
  }
  if (axis.values.empty()) throw InputError("--set '" + text + "': no values");
  for (double v : axis.values)
    if (!std::isfinite(v)) throw InputError("--set '" + text + "': " + formatValue(v) + " is not a finite number");
  return axis;
}

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

bool caseComplete(const fs::path& run) {
  std::ifstream in(run / "summary.json");
  if (!in) return false;
  try {
    const auto j = nlohmann::json::parse(in);
    const std::string reason = j.value("stop_reason", "");
    return reason == "delta_max" || reason == "failure";
  } catch (const std::exception&) {
    return false;
  }
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The running cases, for the signal handler: it stops launching and passes the signal on.
constexpr int kMaxJobs = 256;
std::atomic<bool> sweepStopRequested{false};
std::atomic<pid_t> runningCase[kMaxJobs];
extern "C" void stopSweep(int signal) {
  sweepStopRequested = true;
  for (auto& pid : runningCase)
    if (const pid_t p = pid.load(); p > 0) ::kill(p, signal);  // async-signal-safe
}

struct SweepCase {
  std::vector<double> values;
  std::string scene;  // the scene text of the case
  fs::path dir;
};

// A sweep folder is one study: one base scene and preset, one set of keys; each case folder holds
// one set of values for good (sweep.json lists them). Cases of this sweep already in the folder
// are found by their values and must hold the same scene; new values are refused unless --extend.
std::vector<SweepCase> placeCases(const fs::path& dir, const std::vector<std::string>& keys, std::vector<SweepCase> cases,
                                  bool extend, const std::string& baseDigest, nlohmann::json& manifest) {
  manifest = {{"keys", keys}, {"cases", nlohmann::json::array()}, {"base_digest", baseDigest}};
  std::string heldBase = baseDigest;  // of the base scene and preset the folder's cases were made from
  const fs::path manifestFile = dir / "sweep.json";
  std::map<std::vector<double>, fs::path> held;
  int nextNumber = 0;
  if (fs::exists(manifestFile)) {
    nlohmann::json old;
    try {
      old = nlohmann::json::parse(readText(manifestFile));
      if (old.at("keys").get<std::vector<std::string>>() != keys) {
        std::string oldKeys;
        for (const auto& k : old.at("keys")) oldKeys += (oldKeys.empty() ? "" : ", ") + k.get<std::string>();
        throw InputError(dir.string() + ": holds a sweep over " + oldKeys + "; choose another -o for a sweep over other keys");
      }
      heldBase = old.value("base_digest", baseDigest);
      for (const auto& c : old.at("cases")) {
        const std::string name = c.at("directory");
        held[c.at("values").get<std::vector<double>>()] = dir / name;
        manifest["cases"].push_back(c);
        nextNumber = std::max(nextNumber, std::stoi(name.substr(name.find('_') + 1)) + 1);
      }
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError(manifestFile.string() + ": corrupt sweep manifest (" + e.what() + "); choose another -o");
    }
  }
  for (SweepCase& c : cases) {
    std::string values;
    for (std::size_t k = 0; k < keys.size(); ++k) values += (k ? ", " : "") + keys[k] + " = " + formatValue(c.values[k]);
    const auto found = held.find(c.values);
    if (found != held.end()) {
      c.dir = found->second;
      if (fs::exists(c.dir / "scene.toml") && readText(c.dir / "scene.toml") != c.scene)
        throw InputError(c.dir.string() + " holds the case " + values + " of another base scene or preset (its scene.toml "
                         "differs); choose another -o, or remove " + dir.string() + " to start again");
      continue;
    }
    if (!held.empty() && !extend)
      throw InputError(dir.string() + " holds a sweep of other values (not " + values + "); add --extend to add these "
                       "cases to it, or choose another -o");
    if (heldBase != baseDigest)
      throw InputError(dir.string() + " holds a sweep of another base scene or preset; extend it from the same scene and "
                       "preset, or choose another -o");
    char name[32];
    std::snprintf(name, sizeof name, "case_%03d", nextNumber++);
    c.dir = dir / name;
    if (fs::exists(c.dir))
      throw InputError(c.dir.string() + " exists but is not in " + manifestFile.string() + "; choose another -o");
    manifest["cases"].push_back({{"directory", name}, {"values", c.values}});
  }
  return cases;
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
      const fs::path run = cases[c].dir / "run";
      const std::string name = cases[c].dir.filename().string();
      if (caseComplete(run)) {
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "sweep: %s already complete\n", name.c_str());
        continue;
      }
      const bool resume = fs::exists(run / "checkpoint.h5");
      std::vector<std::string> command{self, "run"};
      if (resume) command.insert(command.end(), {"--resume", run.string()});
      else command.insert(command.end(), {(cases[c].dir / "scene.toml").string(), "-o", run.string()});
      command.insert(command.end(), {"--no-plot", "--threads", std::to_string(threads)});
      {
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "sweep: %s %s\n", resume ? "resuming" : "running", name.c_str());
      }
      const pid_t pid = startProcess(command, (cases[c].dir / "log.txt").string());
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
                     (cases[c].dir / "log.txt").c_str());
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker, j);
  for (auto& t : pool) t.join();
  return sweepStopRequested ? 130 : failure.load();
}

// The table of response parameters of every complete case in the folder (sweep.csv, sweep.h5).
int writeTable(const fs::path& dir, const std::vector<std::string>& keys, const nlohmann::json& manifest) {
  std::string csv = "case";
  for (const std::string& key : keys) csv += "," + key;
  csv += ",peak_load_N,delta_at_peak_mm,stiffness_N_per_mm,loading_energy_mJ,loading_energy_to_end_mJ,"
         "failure_deflection_mm,block_displacement_at_failure_mm,load_drops,energy_residual_fraction,failure_mode,"
         "stop_reason,fallen,wall_seconds\n";
  std::vector<std::vector<double>> rowsValues, rowsTable;
  std::vector<std::string> caseNames, modes, reasons;
  for (const auto& entry : manifest["cases"]) {
    const fs::path run = dir / entry["directory"].get<std::string>() / "run";
    if (!caseComplete(run)) continue;  // an interrupted or failed case is never tabled or plotted
    const nlohmann::json j = nlohmann::json::parse(readText(run / "summary.json"));
    const std::vector<double> caseValues = entry["values"];
    const auto& r = j["response"];
    std::ostringstream line;
    line << entry["directory"].get<std::string>();
    for (double v : caseValues) line << "," << v;
    // Missing (no failure): NaN in the table, empty in the CSV.
    const auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : std::nan(""); };
    const double work = r["energy"]["work_mJ"];
    const std::vector<double> values{r["peak_load_N"], r["delta_at_peak_mm"], r["stiffness_N_per_mm"], r["loading_energy_mJ"],
                                     r["loading_energy_to_end_mJ"], number(r["failure_deflection_mm"]),
                                     number(r["block_displacement_at_failure_mm"]), static_cast<double>(r["load_drops"].size()),
                                     work > 0 ? r["energy"]["residual_mJ"].get<double>() / work : 0.0,
                                     j["run"]["wall_seconds"].get<double>()};
    for (std::size_t k = 0; k + 1 < values.size(); ++k) {
      line << ",";
      if (!std::isnan(values[k])) line << values[k];
    }
    std::string fallen;
    for (const auto& f : r["fallen"]) fallen += (fallen.empty() ? "" : " ") + f["name"].get<std::string>();
    line << "," << r["failure_mode"].get<std::string>() << "," << j["stop_reason"].get<std::string>() << "," << fallen << ","
         << j["run"]["wall_seconds"].get<double>() << "\n";
    csv += line.str();
    rowsValues.push_back(caseValues);
    rowsTable.push_back(values);
    caseNames.push_back(entry["directory"]);
    reasons.push_back(j["stop_reason"]);
    modes.push_back(r["failure_mode"]);
  }
  writeTextFileSafely(dir / "sweep.csv", csv);
  writeSweepTable((dir / "sweep.h5").string(), keys, rowsValues,
                  {"peak_load_N", "delta_at_peak_mm", "stiffness_N_per_mm", "loading_energy_mJ", "loading_energy_to_end_mJ",
                   "failure_deflection_mm", "block_displacement_at_failure_mm", "load_drops", "energy_residual_fraction",
                   "wall_seconds"},
                  rowsTable, caseNames, modes, reasons);
  return static_cast<int>(caseNames.size());
}

int runSweep(const SweepArguments& a) {
  if (a.threads < 1) throw InputError("--threads must be at least 1 per case, got " + std::to_string(a.threads));
  if (a.jobs < 0 || a.jobs > kMaxJobs)
    throw InputError("--jobs must be 0 (cores / threads) to " + std::to_string(kMaxJobs) + ", got " + std::to_string(a.jobs));
  if (a.maxCases < 1) throw InputError("--max-cases must be at least 1");
  std::vector<Axis> axes;
  for (const auto& s : a.sets) axes.push_back(parseAxis(s, a.maxCases));
  if (axes.empty()) throw InputError("give at least one --set KEY=values (e.g. --set E=3.3e9,4.2e9)");
  std::vector<std::string> keys;
  for (const Axis& axis : axes) keys.push_back(axis.key);

  // Every case: the Cartesian product of the axes, the first axis varying slowest; with --zip,
  // the k-th value of every axis together. Counted before anything is made.
  long count = a.zip ? static_cast<long>(axes[0].values.size()) : 1;
  for (const Axis& axis : axes) {
    if (a.zip && axis.values.size() != axes[0].values.size())
      throw InputError("--zip: every --set needs the same number of values (" + axes[0].key + " has " +
                       std::to_string(axes[0].values.size()) + ", " + axis.key + " has " + std::to_string(axis.values.size()) + ")");
    if (!a.zip) count = count > a.maxCases ? count : count * static_cast<long>(axis.values.size());
  }
  if (count > a.maxCases)
    throw InputError("the --set values make " + (count > 1000000 ? std::string("more than a million") : std::to_string(count)) +
                     " cases, more than --max-cases " + std::to_string(a.maxCases) +
                     "; give fewer values, or raise --max-cases if you mean it");
  std::vector<std::vector<double>> values{{}};
  if (a.zip) {
    values.assign(axes[0].values.size(), {});
    for (const Axis& axis : axes)
      for (std::size_t c = 0; c < values.size(); ++c) values[c].push_back(axis.values[c]);
  } else {
    for (const Axis& axis : axes) {
      std::vector<std::vector<double>> next;
      for (const auto& c : values)
        for (double v : axis.values) {
          auto d = c;
          d.push_back(v);
          next.push_back(d);
        }
      values = next;
    }
  }
  std::vector<SweepCase> cases;
  for (const auto& v : values) {
    // The preset's keys first: a --set of the same key wins.
    std::vector<std::pair<std::string, double>> overrides =
        a.preset.empty() ? std::vector<std::pair<std::string, double>>{} : findPreset(a.preset).overrides;
    for (std::size_t k = 0; k < axes.size(); ++k) overrides.emplace_back(axes[k].key, v[k]);
    cases.push_back({v, sceneWithOverrides(a.scene, overrides), {}});
    try {  // every case a valid scene before anything is made
      readSceneText(cases.back().scene, a.scene);
    } catch (const InputError& e) {
      throw InputError("case " + std::to_string(cases.size() - 1) + " of the sweep is not a valid scene: " + e.what());
    }
  }

  const fs::path dir(a.output);
  requireWritableDirectory(a.output);
  const FolderLock lock(a.output, "a sweep");
  nlohmann::json manifest;
  cases = placeCases(dir, keys, cases, a.extend, textDigest(readText(a.scene) + "\npreset " + a.preset), manifest);
  // The manifest first, then the case scenes: a sweep stopped in between is found again by its values.
  manifest["scene"] = fs::absolute(a.scene).string();
  manifest["preset"] = a.preset;
  writeTextFileSafely(dir / "sweep.json", manifest.dump(2) + "\n");
  for (const SweepCase& c : cases) {
    fs::create_directories(c.dir);
    if (!fs::exists(c.dir / "scene.toml")) writeTextFileSafely(c.dir / "scene.toml", c.scene);
  }

  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, cores / static_cast<unsigned>(a.threads)));
  std::signal(SIGINT, stopSweep);
  std::signal(SIGTERM, stopSweep);
  const int status = runCases(cases, std::min<int>(jobs, static_cast<int>(cases.size())), a.threads);
  const int complete = writeTable(dir, keys, manifest);
  std::printf("sweep: %d of %zu cases in %s complete; table %s (and sweep.h5)\n", complete, manifest["cases"].size(),
              a.output.c_str(), (dir / "sweep.csv").c_str());
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

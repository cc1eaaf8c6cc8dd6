// tessera sweep: a scene run over a list (or grid) of parameter values, cases in parallel;
// tessera report: the paper's figures from a sweep.
#include "geometry/input_error.h"
#include "solver/presets.h"
#include "solver/run_output.h"
#include "solver/scene.h"
#include "tools/commands.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
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

struct Axis {
  std::string key;  // table.key
  std::vector<double> values;
};

// "KEY=v1,v2,..." or "KEY=first:last:count" (count values evenly spaced, ends included).
Axis parseAxis(const std::string& text) {
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
      const int count = std::stoi(n);
      if (count < 1) throw std::invalid_argument("count");
      for (int k = 0; k < count; ++k) axis.values.push_back(count == 1 ? first : first + (last - first) * k / (count - 1));
    } else {
      std::stringstream in(values);
      std::string v;
      while (std::getline(in, v, ',')) axis.values.push_back(std::stod(v));
    }
  } catch (const std::exception&) {
    throw InputError("--set '" + text + "': values must be numbers (SI units), e.g. E=3.3e9,4.2e9 or mu=0.2:1:5");
  }
  if (axis.values.empty()) throw InputError("--set '" + text + "': no values");
  return axis;
}

struct SweepArguments {
  std::string scene, output;
  std::string preset;  // applied to every case
  std::vector<std::string> sets;
  int jobs = 0;     // 0: one per core
  int threads = 1;  // per case
  bool zip = false; // axes varied together, not as a grid
};

std::string selfExecutable() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("tessera") : self.string();
}

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

std::string formatValue(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

void runSweep(const SweepArguments& a) {
  std::vector<Axis> axes;
  for (const auto& s : a.sets) axes.push_back(parseAxis(s));
  if (axes.empty()) throw InputError("give at least one --set KEY=values (e.g. --set E=3.3e9,4.2e9)");

  // Every case: the Cartesian product of the axes, the first axis varying slowest; with --zip,
  // the k-th value of every axis together.
  std::vector<std::vector<double>> cases{{}};
  if (a.zip) {
    cases.assign(axes[0].values.size(), {});
    for (const Axis& axis : axes) {
      if (axis.values.size() != cases.size())
        throw InputError("--zip: every --set needs the same number of values (" + axes[0].key + " has " +
                         std::to_string(cases.size()) + ", " + axis.key + " has " + std::to_string(axis.values.size()) + ")");
      for (std::size_t c = 0; c < cases.size(); ++c) cases[c].push_back(axis.values[c]);
    }
  } else {
    for (const Axis& axis : axes) {
      std::vector<std::vector<double>> next;
      for (const auto& c : cases)
        for (double v : axis.values) {
          auto d = c;
          d.push_back(v);
          next.push_back(d);
        }
      cases = next;
    }
  }

  // Write (and so validate) every case's scene before running anything.
  const fs::path dir(a.output);
  std::vector<fs::path> caseDirs;
  std::vector<std::string> texts;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    // The preset's keys first: a --set of the same key wins.
    std::vector<std::pair<std::string, double>> overrides =
        a.preset.empty() ? std::vector<std::pair<std::string, double>>{} : findPreset(a.preset).overrides;
    for (std::size_t k = 0; k < axes.size(); ++k) overrides.emplace_back(axes[k].key, cases[c][k]);
    texts.push_back(sceneWithOverrides(a.scene, overrides));
    char name[32];
    std::snprintf(name, sizeof name, "case_%03zu", c);
    caseDirs.push_back(dir / name);
  }
  // A case folder holds one case for good: a folder from a sweep of other values, another base
  // scene or preset is refused, never relabelled (re-running the same sweep finishes what is missing).
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const fs::path scene = caseDirs[c] / "scene.toml";
    if (!fs::exists(scene)) continue;
    std::ifstream in(scene);
    const std::string held((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (held != texts[c]) {
      std::string values;
      for (std::size_t k = 0; k < axes.size(); ++k) values += (k ? ", " : "") + axes[k].key + " = " + formatValue(cases[c][k]);
      throw InputError(caseDirs[c].string() + " holds a case of another sweep (its scene.toml differs from this sweep's " +
                       values + "); choose another -o, or remove " + dir.string() + " to start again");
    }
  }
  for (std::size_t c = 0; c < cases.size(); ++c) {
    fs::create_directories(caseDirs[c]);
    const fs::path scene = caseDirs[c] / "scene.toml";
    std::ofstream(scene) << texts[c];
    try {
      readScene(scene.string());
    } catch (const InputError& e) {
      fs::remove_all(dir);
      throw InputError(std::string("case ") + std::to_string(c) + " of the sweep is not a valid scene: " + e.what());
    }
  }
  nlohmann::json manifest = {{"scene", fs::absolute(a.scene).string()}, {"keys", nlohmann::json::array()}, {"cases", nlohmann::json::array()}};
  for (const Axis& axis : axes) manifest["keys"].push_back(axis.key);
  for (std::size_t c = 0; c < cases.size(); ++c)
    manifest["cases"].push_back({{"directory", caseDirs[c].filename().string()}, {"values", cases[c]}});
  std::ofstream(dir / "sweep.json") << manifest.dump(2) << "\n";

  // Run the cases, `jobs` at a time; each is an ordinary `tessera run`.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, cores / std::max(1, a.threads)));
  const std::string self = selfExecutable();
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex print;
  const auto worker = [&] {
    for (std::size_t c; (c = next++) < cases.size();) {
      const fs::path run = caseDirs[c] / "run";
      if (caseComplete(run)) {
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "sweep: %s already complete\n", caseDirs[c].filename().c_str());
        continue;
      }
      const bool resume = fs::exists(run / "checkpoint.h5");
      const std::string command = "'" + self + "' run " +
                                  (resume ? "--resume '" + run.string() + "'"
                                          : "'" + (caseDirs[c] / "scene.toml").string() + "' -o '" + run.string() + "'") +
                                  " --no-plot --threads " + std::to_string(a.threads) + " > '" +
                                  (caseDirs[c] / "log.txt").string() + "' 2>&1";
      {
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "sweep: %s %s\n", resume ? "resuming" : "running", caseDirs[c].filename().c_str());
      }
      const int raw = std::system(command.c_str());
      const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128;
      std::lock_guard<std::mutex> lock(print);
      if (status != 0) {
        failed = true;
        std::fprintf(stderr, "sweep: %s stopped with status %d (see %s)\n", caseDirs[c].filename().c_str(), status,
                     (caseDirs[c] / "log.txt").c_str());
      } else {
        std::fprintf(stderr, "sweep: %s done\n", caseDirs[c].filename().c_str());
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  // The table of response parameters.
  std::ofstream csv(dir / ".tmp-sweep.csv");
  csv << "case";
  for (const Axis& axis : axes) csv << "," << axis.key;
  csv << ",peak_load_N,delta_at_peak_mm,stiffness_N_per_mm,loading_energy_mJ,loading_energy_to_end_mJ,"
         "failure_deflection_mm,block_displacement_at_failure_mm,load_drops,energy_residual_fraction,failure_mode,"
         "stop_reason,fallen,wall_seconds\n";
  std::vector<std::vector<double>> rowsValues, rowsTable;
  std::vector<std::string> caseNames, modes, reasons;
  int complete = 0;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    std::ifstream in(caseDirs[c] / "run" / "summary.json");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const std::exception&) {
      continue;
    }
    ++complete;
    const auto& r = j["response"];
    csv << caseDirs[c].filename().string();
    for (double v : cases[c]) csv << "," << v;
    // Missing (no failure): NaN in the table, empty in the CSV.
    const auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : std::nan(""); };
    const double work = r["energy"]["work_mJ"];
    const std::vector<double> values{r["peak_load_N"], r["delta_at_peak_mm"], r["stiffness_N_per_mm"], r["loading_energy_mJ"],
                                     r["loading_energy_to_end_mJ"], number(r["failure_deflection_mm"]),
                                     number(r["block_displacement_at_failure_mm"]), static_cast<double>(r["load_drops"].size()),
                                     work > 0 ? r["energy"]["residual_mJ"].get<double>() / work : 0.0,
                                     j["run"]["wall_seconds"].get<double>()};
    for (std::size_t k = 0; k + 1 < values.size(); ++k) {
      csv << ",";
      if (!std::isnan(values[k])) csv << values[k];
    }
    rowsValues.push_back(cases[c]);
    rowsTable.push_back(values);
    caseNames.push_back(caseDirs[c].filename().string());
    reasons.push_back(j["stop_reason"]);
    std::string fallen;
    for (const auto& f : r["fallen"]) fallen += (fallen.empty() ? "" : " ") + f["name"].get<std::string>();
    csv << "," << r["failure_mode"].get<std::string>() << "," << j["stop_reason"].get<std::string>() << "," << fallen << ","
        << j["run"]["wall_seconds"].get<double>() << "\n";
    modes.push_back(r["failure_mode"]);
  }
  csv.close();
  fs::rename(dir / ".tmp-sweep.csv", dir / "sweep.csv");
  std::vector<std::string> keys;
  for (const Axis& axis : axes) keys.push_back(axis.key);
  writeSweepTable((dir / "sweep.h5").string(), keys, rowsValues,
                  {"peak_load_N", "delta_at_peak_mm", "stiffness_N_per_mm", "loading_energy_mJ", "loading_energy_to_end_mJ",
                   "failure_deflection_mm", "block_displacement_at_failure_mm", "load_drops", "energy_residual_fraction",
                   "wall_seconds"},
                  rowsTable, caseNames, modes, reasons);
  std::printf("sweep: %d of %zu cases complete; table %s (and sweep.h5)\n", complete, cases.size(),
              (dir / "sweep.csv").c_str());
  std::printf("draw the figures with: tessera report %s\n", a.output.c_str());
  if (failed) throw CLI::RuntimeError(130);
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
  cmd->footer("Example (the paper's E study): tessera sweep assets/scenes/default.toml -o out/E \\\n"
              "  --set E=3.3e9,4.2e9,5e9,7.5e9,10e9,20e9,30e9,50e9,75e9\n"
              "Re-running a sweep finishes only the missing cases (and resumes stopped ones).");
  cmd->callback([args] { runSweep(*args); });

  auto report = std::make_shared<std::pair<std::string, std::string>>();
  CLI::App* rep = app.add_subcommand("report", "Draw the paper's figures (PNG and SVG) from a sweep directory.");
  rep->add_option("sweep", report->first, "Sweep directory")->required();
  rep->add_option("--experiments", report->second,
                  "CSV of experimental points (label, E_Pa, L_m, h_m, P_peak_N, delta_peak_m) for the normalised plot");
  rep->callback([report] {
    const fs::path script = fs::path(TESSERA_SOURCE_DIR) / "tools" / "plot" / "report_sweep.py";
    std::string command = "/usr/bin/python3 '" + script.string() + "' '" + report->first + "'";
    if (!report->second.empty()) command += " --experiments '" + report->second + "'";
    if (std::system(command.c_str()) != 0)
      throw InputError(report->first + ": could not draw the report (needs Debian's python3-matplotlib and a sweep.csv)");
  });
}

}  // namespace tessera::tools

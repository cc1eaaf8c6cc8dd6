#include "run/sweep.h"
#include "io/json_text.h"

#include "io/file_digest.h"
#include "io/folder_lock.h"
#include "io/input_error.h"
#include "io/text_file.h"
#include "io/safe_write.h"
#include "run/presets.h"
#include "run/run_output.h"
#include "run/run_summary.h"
#include "run/scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iterator>
#include <map>
#include <sstream>

#include <unistd.h>

namespace tessera {

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
      old = nlohmann::json::parse(readTextFile(manifestFile));
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
      c.dir = found->second.string();
      if (fs::exists(fs::path(c.dir) / "scene.toml") && readTextFile(fs::path(c.dir) / "scene.toml") != c.scene)
        throw InputError(c.dir + " holds the case " + values + " of another base scene or preset (its scene.toml "
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
    c.dir = (dir / name).string();
    if (fs::exists(c.dir))
      throw InputError(c.dir + " exists but is not in " + manifestFile.string() + "; choose another -o");
    manifest["cases"].push_back({{"directory", name}, {"values", c.values}});
  }
  return cases;
}

}  // namespace

// "KEY=v1,v2,..." or "KEY=first:last:count" (count values evenly spaced, ends included).
SweepAxis parseSweepAxis(const std::string& text, long maxCases) {
  const auto eq = text.find('=');
  const std::string form = "give KEY=v1,v2,... or KEY=first:last:count, numbers in SI units (e.g. E=3.3e9,4.2e9 or mu=0.2:1:5)";
  if (eq == std::string::npos || eq == 0) throw InputError("--set '" + text + "': " + form);
  SweepAxis axis;
  axis.key = text.substr(0, eq);
  if (kAliases.count(axis.key)) axis.key = kAliases.at(axis.key);
  const std::string values = text.substr(eq + 1);
  // Each value whole, or refused: "2.5mm", "0.2;0.3" or "0.2:0.3" would otherwise be read as
  // their first number and sweep values nobody asked for.
  const auto part = [&](const std::string& word, bool integer) {
    const auto begin = word.find_first_not_of(" \t"), end = word.find_last_not_of(" \t");
    const std::string trimmed = begin == std::string::npos ? "" : word.substr(begin, end - begin + 1);
    std::size_t used = 0;
    double v = 0;
    try {
      v = integer ? static_cast<double>(std::stol(trimmed, &used)) : std::stod(trimmed, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (trimmed.empty() || used != trimmed.size())
      throw InputError("--set '" + text + "': '" + word + "' is not " + (integer ? "a whole count" : "a number") + "; " + form);
    return v;
  };
  if (std::count(values.begin(), values.end(), ':') == 2) {
    std::stringstream in(values);
    std::string a, b, n;
    std::getline(in, a, ':');
    std::getline(in, b, ':');
    std::getline(in, n);
    const double first = part(a, false), last = part(b, false);
    const long count = static_cast<long>(part(n, true));
    if (count < 1) throw InputError("--set '" + text + "': the count must be at least 1; " + form);
    if (count > maxCases)
      throw InputError("--set '" + text + "': " + std::to_string(count) + " values, more than --max-cases " +
                       std::to_string(maxCases) + "; give fewer, or raise --max-cases if you mean it");
    for (int k = 0; k < count; ++k) axis.values.push_back(count == 1 ? first : first + (last - first) * k / (count - 1));
  } else {
    std::stringstream in(values);
    std::string v;
    while (std::getline(in, v, ',')) axis.values.push_back(part(v, false));
  }
  if (axis.values.empty()) throw InputError("--set '" + text + "': no values; " + form);
  for (double v : axis.values)
    if (!std::isfinite(v)) throw InputError("--set '" + text + "': " + formatValue(v) + " is not a finite number");
  std::vector<double> sorted = axis.values;
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice != sorted.end())  // identical cases, each labelled as if it were another
    throw InputError("--set '" + text + "': " + formatValue(*twice) + " is given twice; give each value once");
  return axis;
}

std::vector<SweepCase> sweepCases(const SweepPlan& plan) {
  if (plan.maxCases < 1) throw InputError("--max-cases must be at least 1");
  const std::vector<SweepAxis>& axes = plan.axes;
  if (axes.empty()) throw InputError("give at least one --set KEY=values (e.g. --set E=3.3e9,4.2e9)");
  // Every case: the Cartesian product of the axes, the first axis varying slowest; with --zip,
  // the k-th value of every axis together. Counted before anything is made.
  long count = plan.zip ? static_cast<long>(axes[0].values.size()) : 1;
  for (const SweepAxis& axis : axes) {
    if (plan.zip && axis.values.size() != axes[0].values.size())
      throw InputError("--zip: every --set needs the same number of values (" + axes[0].key + " has " +
                       std::to_string(axes[0].values.size()) + ", " + axis.key + " has " + std::to_string(axis.values.size()) + ")");
    if (!plan.zip) count = count > plan.maxCases ? count : count * static_cast<long>(axis.values.size());
  }
  if (count > plan.maxCases)
    throw InputError("the --set values make " + (count > 1000000 ? std::string("more than a million") : std::to_string(count)) +
                     " cases, more than --max-cases " + std::to_string(plan.maxCases) +
                     "; give fewer values, or raise --max-cases if you mean it");
  std::vector<std::vector<double>> values{{}};
  if (plan.zip) {
    values.assign(axes[0].values.size(), {});
    for (const SweepAxis& axis : axes)
      for (std::size_t c = 0; c < values.size(); ++c) values[c].push_back(axis.values[c]);
  } else {
    for (const SweepAxis& axis : axes) {
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
        plan.preset.empty() ? std::vector<std::pair<std::string, double>>{} : findPreset(plan.preset).overrides;
    for (std::size_t k = 0; k < axes.size(); ++k) overrides.emplace_back(axes[k].key, v[k]);
    cases.push_back({v, sceneWithOverrides(plan.scene, overrides), {}});
    try {  // every case a valid scene before anything is made
      readSceneText(cases.back().scene, plan.scene);
    } catch (const InputError& e) {
      throw InputError("case " + std::to_string(cases.size() - 1) + " of the sweep is not a valid scene: " + e.what());
    }
  }

  return cases;
}

std::vector<SweepCase> placeSweepCases(const std::string& folder, const SweepPlan& plan, std::vector<SweepCase> cases,
                                       bool extend) {
  const fs::path dir(folder);
  std::vector<std::string> keys;
  for (const SweepAxis& axis : plan.axes) keys.push_back(axis.key);
  nlohmann::json manifest;
  cases = placeCases(dir, keys, cases, extend, textDigest(readTextFile(plan.scene) + "\npreset " + plan.preset), manifest);
  // The manifest first, then the case scenes: a sweep stopped in between is found again by its values.
  manifest["scene"] = fs::absolute(plan.scene).string();
  manifest["preset"] = plan.preset;
  writeTextFileSafely(dir / "sweep.json", jsonText(manifest));
  for (const SweepCase& c : cases) {
    fs::create_directories(c.dir);
    if (!fs::exists(fs::path(c.dir) / "scene.toml")) writeTextFileSafely(fs::path(c.dir) / "scene.toml", c.scene);
  }
  return cases;
}

std::vector<SweepCase> readSweepFolder(const std::string& folder) {
  const fs::path dir(folder), manifestFile = dir / "sweep.json";
  if (!fs::is_directory(dir)) throw InputError(folder + ": no such sweep folder; give the -o folder of tessera sweep");
  if (!fs::exists(manifestFile))
    throw InputError(folder + ": not a sweep folder (no sweep.json); give the -o folder of tessera sweep");
  std::vector<SweepCase> cases;
  try {
    const nlohmann::json manifest = nlohmann::json::parse(readTextFile(manifestFile));
    for (const auto& c : manifest.at("cases")) {
      const fs::path caseDir = dir / c.at("directory").get<std::string>();
      // A case not placed yet (its folder made by a sweep that stopped first) has no scene.
      const fs::path scene = caseDir / "scene.toml";
      cases.push_back({c.at("values").get<std::vector<double>>(), fs::exists(scene) ? readTextFile(scene) : std::string(),
                       caseDir.string()});
      sweepCaseNumber(cases.back().dir);  // a name of the form case_N
    }
  } catch (const std::exception& e) {
    throw InputError(manifestFile.string() + ": corrupt sweep manifest (" + e.what() + "); run the sweep again into a new -o");
  }
  return cases;
}

int sweepCaseNumber(const std::string& caseDir) {
  const std::string name = fs::path(caseDir).filename().string();
  std::size_t end = 0;
  const int number = name.rfind("case_", 0) == 0 ? std::stoi(name.substr(5), &end) : -1;
  if (number < 0 || end != name.size() - 5) throw std::invalid_argument("'" + name + "' is not a case folder (case_N)");
  return number;
}

const char* caseStateName(CaseState state) {
  switch (state) {
    case CaseState::Complete: return "complete";
    case CaseState::Running: return "running";
    case CaseState::Interrupted: return "interrupted";
    case CaseState::Failed: return "failed";
    case CaseState::Missing: return "missing";
    case CaseState::Queued: return "queued";
    case CaseState::Unknown: return "unknown";
  }
  return "?";
}

namespace {

std::string hostName() {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return host;
}

}  // namespace

CaseState deadAttemptState(const std::string& caseDir) {
  return fs::exists(fs::path(caseDir) / "run" / "checkpoint.h5") ? CaseState::Interrupted : CaseState::Failed;
}

CaseStatus sweepCaseStatus(const std::string& caseDir) {
  const fs::path dir(caseDir), run = dir / "run";
  CaseStatus status;
  bool started = false;
  try {
    const nlohmann::json attempt = nlohmann::json::parse(readTextFile(dir / "attempt.json"));
    started = attempt.at("state") == "started";
    status.exitStatus = started ? -1 : attempt.at("exit_status").get<int>();
    status.slurmJob = attempt.value("slurm_job", "");
    status.host = attempt.value("host", "");
  } catch (const std::exception&) {
    // none recorded (never started by a runner): the files below tell
  }
  if (sweepCaseComplete(run.string())) {
    status.state = CaseState::Complete;
  } else if (folderLockHolder(caseDir) != 0) {
    status.state = CaseState::Running;
  } else if (started) {
    // Its runner has not recorded an end: alive elsewhere, or killed (here: its lock is free).
    status.startedElsewhere = status.host != hostName();
    status.state = status.startedElsewhere ? CaseState::Running : deadAttemptState(caseDir);
  } else if (status.exitStatus == 130 || status.exitStatus == 128 + 15) {
    status.state = CaseState::Interrupted;  // stopped by SIGINT or SIGTERM, its checkpoint written
  } else if (status.exitStatus >= 0) {
    status.state = CaseState::Failed;  // 2 bad input, 3 unstable, 128 + n killed by signal n; 0 with no complete summary
  } else if (fs::exists(run / "checkpoint.h5")) {
    status.state = CaseState::Interrupted;
  } else if (fs::exists(run) || fs::exists(dir / "log.txt")) {
    status.state = CaseState::Failed;
  } else {
    status.state = CaseState::Missing;
  }
  return status;
}

void recordCaseAttempt(const std::string& caseDir, int exitStatus, const std::string& slurmJob) {
  nlohmann::json attempt = {{"state", exitStatus < 0 ? "started" : "ended"}, {"host", hostName()},
                            {"pid", static_cast<long>(::getpid())}, {"slurm_job", slurmJob}};
  if (exitStatus >= 0) attempt["exit_status"] = exitStatus;
  writeTextFileSafely(fs::path(caseDir) / "attempt.json", jsonText(attempt));
}

bool sweepCaseComplete(const std::string& runDir) {
  try {
    return isComplete(readRunSummary(runDir).stopReason);
  } catch (const InputError&) {
    return false;  // missing, cut short or not a summary: the case runs again
  }
}

namespace {

// Missing (no failure): NaN in the table, empty in the CSV.
double number(const nlohmann::json& v) { return v.is_number() ? v.get<double>() : std::nan(""); }

// One numeric column of the sweep tables (after the case's keys): its name, summary.json's where
// it is one of its response parameters, and its value from a case's summary as the file has it
// (runSummaryJson: the file's keys and units).
struct SweepColumn {
  std::string name;
  std::function<double(const nlohmann::json& summary)> value;
};

const std::vector<SweepColumn>& sweepColumns() {
  static const std::vector<SweepColumn> columns = [] {
    std::vector<SweepColumn> c;
    for (const char* name : {"peak_load_N", "delta_at_peak_mm", "stiffness_N_per_mm", "loading_energy_mJ", "loading_energy_to_end_mJ",
                             "failure_deflection_mm", "block_displacement_at_failure_mm"})
      c.push_back({name, [name](const nlohmann::json& j) { return number(j.at("response").at(name)); }});
    c.push_back({"load_drops", [](const nlohmann::json& j) { return static_cast<double>(j.at("response").at("load_drops").size()); }});
    c.push_back({"energy_residual_fraction", [](const nlohmann::json& j) {
                   const nlohmann::json& e = j.at("response").at("energy");
                   const double work = e.at("external_work_mJ");
                   return work > 0 ? e.at("energy_residual_mJ").get<double>() / work : 0.0;
                 }});
    c.push_back({"wall_seconds", [](const nlohmann::json& j) { return number(j.at("run").at("wall_seconds")); }});
    return c;
  }();
  return columns;
}

}  // namespace

// The table of response parameters of every complete case in the folder (sweep.csv, sweep.h5):
// the case's keys, sweepColumns(), then its failure mode, stop reason and the bodies out.
int writeSweepTables(const std::string& folder) {
  const fs::path dir(folder);
  // One writer at a time: each reads every case and writes the whole table, so a later writer
  // never replaces a table with one that misses a case completed meanwhile.
  const FileLock lock((dir / ".tables.lock").string());
  const nlohmann::json manifest = nlohmann::json::parse(readTextFile(dir / "sweep.json"));
  const std::vector<std::string> keys = manifest.at("keys");
  std::vector<std::string> names;
  for (const SweepColumn& c : sweepColumns()) names.push_back(c.name);
  std::string csv = "case";
  for (const std::string& name : keys) csv += "," + name;
  for (const std::string& name : names) csv += "," + name;
  csv += ",failure_mode,stop_reason,fallen\n";
  std::vector<std::vector<double>> rowsValues, rowsTable;
  std::vector<std::string> caseNames, modes, reasons;
  for (const auto& entry : manifest["cases"]) {
    const fs::path run = dir / entry["directory"].get<std::string>() / "run";
    RunSummary summary;
    try {
      summary = readRunSummary(run);
    } catch (const InputError&) {
      continue;  // not run yet, or cut short: not tabled
    }
    if (!isComplete(summary.stopReason)) continue;  // an interrupted or failed case is never tabled or plotted
    const nlohmann::json j = runSummaryJson(summary);
    const std::vector<double> caseValues = entry["values"];
    std::vector<double> values;
    for (const SweepColumn& c : sweepColumns()) values.push_back(c.value(j));
    std::ostringstream line;
    line << entry["directory"].get<std::string>();
    for (double v : caseValues) line << "," << v;
    for (double v : values) {
      line << ",";
      if (!std::isnan(v)) line << v;
    }
    std::string fallen;
    for (const FallenBody& f : summary.fallen) fallen += (fallen.empty() ? "" : " ") + f.name;
    const std::string reason = stopReasonName(summary.stopReason);
    line << "," << summary.response.failureMode << "," << reason << "," << fallen << "\n";
    csv += line.str();
    rowsValues.push_back(caseValues);
    rowsTable.push_back(values);
    caseNames.push_back(entry["directory"]);
    reasons.push_back(reason);
    modes.push_back(summary.response.failureMode);
  }
  writeTextFileSafely(dir / "sweep.csv", csv);
  writeSweepTable((dir / "sweep.h5").string(), keys, rowsValues, names, rowsTable, caseNames, modes, reasons);
  return static_cast<int>(caseNames.size());
}

}  // namespace tessera

#include "run/slurm_sweep.h"
#include "io/json_text.h"

#include "io/input_error.h"
#include "io/safe_write.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// Seconds of a Slurm time limit already matched by the pattern below: MM, MM:SS, HH:MM:SS,
// D-HH, D-HH:MM, D-HH:MM:SS.
long timeLimitSeconds(const std::string& text) {
  const std::size_t dash = text.find('-');
  std::vector<long> parts;
  std::stringstream in(dash == std::string::npos ? text : text.substr(dash + 1));
  for (std::string part; std::getline(in, part, ':');) parts.push_back(std::stol(part));
  if (dash != std::string::npos) {  // D-HH[:MM[:SS]]
    parts.resize(3, 0);
    return std::stol(text.substr(0, dash)) * 86400 + parts[0] * 3600 + parts[1] * 60 + parts[2];
  }
  if (parts.size() == 3) return parts[0] * 3600 + parts[1] * 60 + parts[2];
  return parts[0] * 60 + (parts.size() == 2 ? parts[1] : 0);
}

}  // namespace

void checkSlurmSettings(const SlurmSettings& s, const std::string& folder) {
  // sbatch reads #SBATCH lines word by word and expands % in file names: a path it would split or
  // rewrite cannot name the sweep's output files.
  if (folder.find_first_of(" \t\n'\"\\%") != std::string::npos)
    throw InputError(folder + ": a sweep folder for --slurm cannot hold spaces, quotes, backslashes or '%' (sbatch "
                     "would split or rewrite it); choose a plain path for -o");
  static const std::regex time(R"(^(\d+-\d+(:\d+){0,2}|\d+(:\d+){0,2}|UNLIMITED|INFINITE)$)");
  if (!s.timeLimit.empty() && !std::regex_match(s.timeLimit, time))
    throw InputError("--time '" + s.timeLimit + "': give Slurm's MM, HH:MM:SS or D-HH:MM:SS, e.g. --time 02:00:00");
  if (!s.timeLimit.empty() && std::isdigit(static_cast<unsigned char>(s.timeLimit[0])) && timeLimitSeconds(s.timeLimit) < 300)
    throw InputError("--time '" + s.timeLimit + "': under 5 minutes, each case would be told to checkpoint and stop (120 s "
                     "before the limit) almost as it starts; give at least 00:05:00");
  static const std::regex name(R"(^[A-Za-z0-9_.,-]+$)");
  if (!s.partition.empty() && !std::regex_match(s.partition, name))
    throw InputError("--partition '" + s.partition + "': a partition name (letters, digits, _ . , -), e.g. --partition compute");
  if (s.cpusPerTask < 1) throw InputError("--cpus-per-task must be at least 1, got " + std::to_string(s.cpusPerTask));
  if (s.maxConcurrent < 0) throw InputError("--max-concurrent must be 0 (no limit) or more, got " + std::to_string(s.maxConcurrent));
  for (const std::string& option : s.extraOptions)
    if (option.rfind("-", 0) != 0 || option.find('\n') != std::string::npos)
      throw InputError("--sbatch '" + option + "': give one sbatch option as written after #SBATCH, e.g. --sbatch=--account=proj42");
}

std::string slurmArraySpec(std::vector<int> numbers, int maxConcurrent) {
  std::sort(numbers.begin(), numbers.end());
  numbers.erase(std::unique(numbers.begin(), numbers.end()), numbers.end());
  std::string spec;
  for (std::size_t i = 0; i < numbers.size();) {
    std::size_t j = i;
    while (j + 1 < numbers.size() && numbers[j + 1] == numbers[j] + 1) ++j;
    spec += (spec.empty() ? "" : ",") + std::to_string(numbers[i]);
    if (j > i) spec += "-" + std::to_string(numbers[j]);
    i = j + 1;
  }
  if (maxConcurrent > 0) spec += "%" + std::to_string(maxConcurrent);
  return spec;
}

std::string slurmSweepScript(const std::string& folderGiven, const std::string& tessera, const SlurmSettings& s,
                             const std::vector<int>& caseNumbers) {
  fs::path normal = fs::path(folderGiven).lexically_normal();
  if (!normal.has_filename()) normal = normal.parent_path();  // "/scratch/E/" names /scratch/E
  const std::string folder = normal.string();
  const auto quoted = [](const std::string& text) {
    std::string q = "'";
    for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  std::string script = "#!/bin/bash\n"
                       "# Tessera sweep " + folder + ": one Slurm array task a case. Task N runs case_N (its\n"
                       "# scene.toml, into case_N/run, its log in case_N/log.txt), resuming it from its checkpoint\n"
                       "# when it has one. SIGTERM (a time limit's warning below, scancel, preemption) makes the\n"
                       "# case checkpoint and stop; resubmitting or requeueing resumes it exactly.\n"
                       "#   tessera sweep " + folder + " --status     where each case stands\n"
                       "#   tessera sweep " + folder + " --resubmit   submit the missing, failed and interrupted cases\n";
  const auto option = [&script](const std::string& text) { script += "#SBATCH " + text + "\n"; };
  option("--job-name=tessera-" + normal.filename().string());
  option("--array=" + slurmArraySpec(caseNumbers, s.maxConcurrent));
  option("--ntasks=1");
  option("--cpus-per-task=" + std::to_string(s.cpusPerTask));
  if (!s.partition.empty()) option("--partition=" + s.partition);
  if (!s.timeLimit.empty()) option("--time=" + s.timeLimit);
  option("--signal=B:TERM@120");
  option("--requeue");
  option("--open-mode=append");
  option("--output=" + (fs::path(folder) / "slurm" / "task_%A_%a.out").string());
  for (const std::string& extra : s.extraOptions) option(extra);
  script += "exec " + quoted(tessera) + " sweep " + quoted(folder) + " --case \"$SLURM_ARRAY_TASK_ID\" --threads \"${SLURM_CPUS_PER_TASK:-" +
            std::to_string(s.cpusPerTask) + "}\"\n";
  return script;
}

SlurmRecord readSlurmRecord(const std::string& folder) {
  const fs::path path = fs::path(folder) / "slurm" / "jobs.json";
  SlurmRecord record;
  std::ifstream in(path);
  if (!in) return record;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    const auto& s = j.at("settings");
    record.settings = {s.at("partition"), s.at("time"), s.at("cpus_per_task"), s.at("max_concurrent"), s.at("sbatch_options")};
    for (const auto& job : j.at("jobs")) record.jobs.push_back({job.at("job_id"), job.at("cases")});
  } catch (const std::exception& e) {
    throw InputError(path.string() + ": corrupt record of Slurm jobs (" + e.what() + "); remove it (the cases' own files "
                     "still tell where they stand)");
  }
  return record;
}

void writeSlurmRecord(const std::string& folder, const SlurmRecord& record) {
  const SlurmSettings& s = record.settings;
  nlohmann::json j = {{"settings",
                       {{"partition", s.partition}, {"time", s.timeLimit}, {"cpus_per_task", s.cpusPerTask},
                        {"max_concurrent", s.maxConcurrent}, {"sbatch_options", s.extraOptions}}},
                      {"jobs", nlohmann::json::array()}};
  for (const SlurmJob& job : record.jobs) j["jobs"].push_back({{"job_id", job.id}, {"cases", job.cases}});
  writeTextFileSafely(fs::path(folder) / "slurm" / "jobs.json", jsonText(j));
}

}  // namespace tessera

#include "tools/plot_scripts.h"

#include "tools/child_process.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <unistd.h>

namespace tessera::tools {

namespace fs = std::filesystem;

std::string plotScript(const std::string& name) {
  const fs::path script = fs::path(selfExecutable()).parent_path().parent_path() / "share" / "tessera" / "plot" / name;
  return fs::is_regular_file(script) ? script.string() : std::string();
}

std::string plotPython() {
  if (const char* chosen = std::getenv("TESSERA_PYTHON"); chosen && *chosen) return chosen;
  if (::access("/usr/bin/python3", X_OK) == 0) return "/usr/bin/python3";
  const char* path = std::getenv("PATH");
  std::istringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');)
    if (!folder.empty() && ::access((fs::path(folder) / "python3").c_str(), X_OK) == 0)
      return (fs::path(folder) / "python3").string();
  return "";
}

int runPlotScript(const std::string& name, const std::vector<std::string>& arguments, const std::string& log) {
  const std::string script = plotScript(name), python = plotPython();
  if (script.empty() || python.empty()) return 127;
  std::vector<std::string> command{python, script};
  command.insert(command.end(), arguments.begin(), arguments.end());
  return waitProcess(startProcess(command, log));
}

}  // namespace tessera::tools

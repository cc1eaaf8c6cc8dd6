#pragma once
#include <string>
#include <vector>

namespace tessera::tools {

/// A plotting script of tools/plot, found beside the executable: <bin>/../share/tessera/plot/NAME
/// (the install tree, and the build tree, where the build copies them). "" if it is missing.
std::string plotScript(const std::string& name);

/// The Python with Debian's numpy and matplotlib: $TESSERA_PYTHON if set, else /usr/bin/python3,
/// else python3 on PATH. "" if there is none.
std::string plotPython();

/// Runs a plot script with `arguments` (no shell); its output appended to `log` ("": this
/// process's). Returns its exit status; 127 when the script or Python is missing.
int runPlotScript(const std::string& name, const std::vector<std::string>& arguments, const std::string& log);

}  // namespace tessera::tools

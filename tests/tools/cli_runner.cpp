#include "tests/tools/cli_runner.h"

#include "tests/fixtures/temp_dir.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace tessera::test {

namespace {
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

CliResult runTessera(const std::string& arguments, const std::string& shell) {
  TempDir capture;
  const std::string command = shell + std::string(" '") + TESSERA_EXE + "' " + arguments + " >'" + (capture / "out") + "' 2>'" +
                              (capture / "err") + "' </dev/null";
  const int raw = std::system(command.c_str());
  CliResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(capture / "out");
  r.err = slurp(capture / "err");
  return r;
}

}  // namespace tessera::test

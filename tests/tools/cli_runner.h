#pragma once
// Runs the tessera executable as a user would, capturing exit status, stdout and stderr.
#include <string>

namespace tessera::test {

struct CliResult {
  int status = -1;
  std::string out, err;
};

/// `arguments` are appended to the executable path as they are (quote them yourself).
CliResult runTessera(const std::string& arguments);

}  // namespace tessera::test

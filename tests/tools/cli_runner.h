#pragma once
// Runs the tessera executable as a user would, capturing exit status, stdout and stderr.
#include <string>

namespace tessera::test {

struct CliResult {
  int status = -1;
  std::string out, err;
};

/// `arguments` are appended to the executable path as they are (quote them with quoted()); `shell`
/// runs before it in the same /bin/sh (e.g. "ulimit -f 40; trap '' XFSZ;" for a small disk).
CliResult runTessera(const std::string& arguments, const std::string& shell = "");

/// A shell-quoted argument.
inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

/// The bundled default block (10 x 10 x 3.18 mm, faces at 5 deg), in mm.
inline const std::string kDefaultBlock = TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj";

}  // namespace tessera::test

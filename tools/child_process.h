#pragma once
#include <string>
#include <sys/types.h>
#include <vector>

namespace tessera::tools {

/// Starts `arguments[0]` (a path) with the other arguments (no shell), its stdout and stderr
/// appended to `log` ("": this process's own), stdin from /dev/null. Returns the child's pid; throws std::runtime_error if it cannot start.
pid_t startProcess(const std::vector<std::string>& arguments, const std::string& log);

/// Waits for a child; returns its exit status, or 128 + the signal that killed it.
int waitProcess(pid_t pid);

/// What a command printed and how it ended.
struct CommandOutput {
  int status = 127;  ///< exit status, 128 + signal, or 127 when the command is not found
  std::string out, err;
};

/// Runs `arguments[0]`, found on PATH, with the other arguments (no shell) and waits for it,
/// keeping its stdout and stderr.
CommandOutput runCommand(const std::vector<std::string>& arguments);

/// The path of the running executable (to start more of itself).
std::string selfExecutable();

}  // namespace tessera::tools

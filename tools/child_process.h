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

/// The path of the running executable (to start more of itself).
std::string selfExecutable();

}  // namespace tessera::tools

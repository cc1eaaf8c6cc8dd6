#pragma once
#include "levelset/assembly_checks.h"

#include <string>

namespace tessera::tools {

/// The warnings and notes of the checks (stderr, prefixed with `command`), then the summary lines
/// printed after writing (bodies, contacts, interlocking, span).
void printAssemblySummary(const Bundle& bundle, const AssemblySummary& summary, const std::string& command);

}  // namespace tessera::tools

#pragma once
#include "levelset/assembly_checks.h"
#include "levelset/rigid_block_analysis.h"
#include "solver/contact_parameters.h"

#include <string>

namespace tessera::tools {

/// The warnings and notes of the checks (stderr, prefixed with `command`), then the summary lines
/// printed after writing (bodies, contacts, interlocking, span).
void printAssemblySummary(const Bundle& bundle, const AssemblySummary& summary, const std::string& command);

/// The friction coefficient of the default scene: the one tile and assemble judge stability at.
inline const double kDefaultFriction = ContactParameters{}.friction;

/// The verdict of the rigid-block checks (interlocked, stable, least friction), as check, tile
/// and assemble print it.
void printAssemblyStatics(const Bundle& bundle, const AssemblyStatics& statics);

}  // namespace tessera::tools

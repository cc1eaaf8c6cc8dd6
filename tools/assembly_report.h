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

/// The most bodies tile and assemble check after writing: the checks' linear programs grow about
/// as the cube of the bodies (0.14 s for a 7 x 7 slab, 11 s for 15 x 15, minutes for 31 x 31).
constexpr std::size_t kVerdictBodyLimit = 150;

/// tile's and assemble's verdict: printAssemblyStatics at the default friction for an assembly of
/// at most kVerdictBodyLimit bodies, else a line naming `tessera check FOLDER`.
void printAssemblyVerdict(const Bundle& bundle, const std::string& folder);

}  // namespace tessera::tools

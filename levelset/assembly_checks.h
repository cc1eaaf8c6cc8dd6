#pragma once
#include "levelset/assembly.h"
#include "levelset/bundle.h"

#include <optional>
#include <string>
#include <vector>

namespace tessera {

/// The output of tile and assemble, checked before any work: not an existing file, not a bundle
/// already (unless `replace`), and a directory that can be created and written. InputError otherwise.
void checkBundleOutput(const std::string& directory, bool replace);

/// The finest voxel of the bundle's shapes, m: the scale of the assembly checks' tolerances.
double finestVoxel(const Bundle& bundle);

/// InputError for the deepest overlap of `check`, if any: "<where>bodies 'a' and 'b' overlap by
/// ... (tolerance ...; N overlapping pair(s) in all); <fix>".
void refuseOverlaps(const Bundle& bundle, const AssemblyCheck& check, double tolerance, const std::string& where,
                    const std::string& fix);

/// What the checks of a new assembly found (tile, assemble).
struct AssemblySummary {
  AssemblyCheck check;
  int locked = 0;  ///< free bodies held both up and down by their neighbours
  std::size_t free = 0;
  std::vector<std::string> warnings;  ///< a body touching nothing
  std::vector<std::string> notes;     ///< a free body not held up and down
};

/// The checks made before an assembly is written: an overlap deeper than the tolerance (default
/// 0.1 of the finest voxel; coincident bodies included) is an InputError naming the two bodies and
/// the fix; a body touching nothing is a warning, a free body not held up and down a note.
/// `gap`: clearance the layout left between neighbours, m.
AssemblySummary checkAssemblyBeforeWriting(const Bundle& bundle, std::optional<double> overlapTolerance, double gap,
                                           const std::string& fix);

}  // namespace tessera

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
  std::vector<std::string> warnings;  ///< a body touching nothing; no free body held
  std::vector<std::string> notes;     ///< a free body not held up and down
};

/// The checks made before an assembly is written: an overlap deeper than the tolerance (default
/// 0.1 of the finest voxel; coincident bodies included) is an InputError naming the two bodies and
/// `overlapFix`. Two or more bodies of which no two touch (blocks laid out apart: a pitch or
/// positions in another unit, a block whose thickness is not along z) are an InputError with
/// `apartFix` when `refuseApart` (a layout tile made: its blocks are meant to touch), else a
/// warning (an assembly may have been modelled with clearances). A body touching nothing is a
/// warning, and so is a slab in which no free body is held both up and down; a free body not held
/// up and down is a note. `gap`: clearance the layout left between neighbours, m.
AssemblySummary checkAssemblyBeforeWriting(const Bundle& bundle, std::optional<double> overlapTolerance, double gap,
                                           const std::string& overlapFix, const std::string& apartFix, bool refuseApart);

}  // namespace tessera

#pragma once
#include "run/indentation.h"
#include "solver/world.h"

#include <string>

namespace tessera {

/// Where a run's checkpoint came from: what `tessera run --resume` needs to rebuild the World.
/// A resumed run must continue with exactly what it started with: the scene text is kept in the
/// checkpoint, and the scene file, bundle and preset are compared by digest before resuming.
struct CheckpointSource {
  std::string scene;        ///< scene file (absolute)
  std::string sceneText;    ///< the scene the run reads (the file's text, or with --preset the text with its keys)
  std::string sceneDigest;  ///< textDigest of the scene file when the run started
  std::string preset;       ///< the --preset name, "" for none
  std::string bundle;       ///< bundle directory (absolute)
  std::string bundleRelative;  ///< the bundle relative to the run folder (found there after moving both)
  std::string bundleDigest;    ///< fileDigest of bundle.h5 when the run started
  int threads = 0;          ///< the thread count (same count: bit-identical continuation)
};

/// Writes the complete state of a run (World, protocol, record) to `path` (HDF5), to a temporary
/// name first, then renamed: a checkpoint is either whole or the previous one.
void writeCheckpoint(const std::string& path, const CheckpointSource& source, const WorldState& world,
                     const IndentationState& state, const IndentationRecord& record);

/// What a message about an unreadable checkpoint says to do.
inline constexpr const char* kUnreadableCheckpointFix =
    "start the run again from its scene in a new folder (a sweep's case: remove its run folder and run the sweep again)";

/// Reads the source of a checkpoint (to rebuild the World and read the scene).
CheckpointSource readCheckpointSource(const std::string& path);

/// Reads a checkpoint into the state of a World made from the same bundle and settings (`world`
/// must come from World::state() of that World), and the protocol and record.
void readCheckpoint(const std::string& path, WorldState& world, IndentationState& state, IndentationRecord& record);

}  // namespace tessera

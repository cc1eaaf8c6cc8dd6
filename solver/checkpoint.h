#pragma once
#include "solver/indentation.h"
#include "solver/world.h"

#include <string>

namespace tessera {

/// Where a run's checkpoint came from: what `tessera run --resume` needs to rebuild the World.
struct CheckpointSource {
  std::string scene;   ///< scene file
  std::string bundle;  ///< bundle directory
  int threads = 0;     ///< the thread count (same count: bit-identical continuation)
};

/// Writes the complete state of a run (World, protocol, record) to `path` (HDF5), to a temporary
/// name first, then renamed: a checkpoint is either whole or the previous one.
void writeCheckpoint(const std::string& path, const CheckpointSource& source, const WorldState& world,
                     const IndentationState& state, const IndentationRecord& record);

/// Reads the source of a checkpoint (to rebuild the World and read the scene).
CheckpointSource readCheckpointSource(const std::string& path);

/// Reads a checkpoint into the state of a World made from the same bundle and settings (`world`
/// must come from World::state() of that World), and the protocol and record.
void readCheckpoint(const std::string& path, WorldState& world, IndentationState& state, IndentationRecord& record);

}  // namespace tessera

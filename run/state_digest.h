#pragma once
#include "solver/world.h"

#include <string>

namespace tessera {

/// A 64-bit FNV-1a digest (io/file_digest.h) of the bodies' state (positions, orientations,
/// velocities, angular momenta: their bytes) and the World's step count and time: two runs with
/// the same digest ended in the same state to the last bit. Written to summary.json.
std::string stateDigest(const World& world);

}  // namespace tessera

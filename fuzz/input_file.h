#pragma once
// The readers take paths: each fuzz input is written to one temporary file per process.
#include <cstddef>
#include <cstdint>
#include <string>

namespace tessera::fuzz {

/// Writes the input to /tmp/tessera-fuzz-<pid><suffix> (overwriting it) and returns that path.
std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& suffix);

}  // namespace tessera::fuzz

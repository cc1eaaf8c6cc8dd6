#include "fuzz/input_file.h"

#include <fstream>
#include <unistd.h>

namespace tessera::fuzz {

std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& suffix) {
  const std::string path = "/tmp/tessera-fuzz-" + std::to_string(::getpid()) + suffix;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                static_cast<std::streamsize>(size));
  return path;
}

}  // namespace tessera::fuzz

#include "io/output_directory.h"

#include "io/input_error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <unistd.h>

namespace tessera {

namespace fs = std::filesystem;

void requireWritableDirectory(const std::string& directory) {
  if (directory.empty()) throw InputError("-o: give an output directory");
  const fs::path dir(directory);
  if (fs::exists(dir) && !fs::is_directory(dir))
    throw InputError(directory + ": exists and is not a directory; give a directory with -o");
  // The first missing ancestor: what this check creates, and removes again.
  fs::path created;
  for (fs::path p = fs::absolute(dir); !p.empty() && !fs::exists(p); p = p.parent_path()) {
    created = p;
    if (p == p.parent_path()) break;
  }
  std::error_code error;
  fs::create_directories(dir, error);
  if (error)
    throw InputError(directory + ": cannot create the output directory (" + error.message() + "); choose another -o");
  const fs::path probe = dir / (".tessera-probe-" + std::to_string(::getpid()));
  bool written = false;
  int reason = 0;
  {
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    if (f) {
      const char bytes[4096] = {};
      written = std::fwrite(bytes, 1, sizeof bytes, f) == sizeof bytes;
      written = (std::fflush(f) == 0) && written;
      if (!written) reason = errno;
      written = (std::fclose(f) == 0) && written;
    } else {
      reason = errno;
    }
  }
  fs::remove(probe, error);
  if (!created.empty()) fs::remove_all(created, error);
  if (!written)
    throw InputError(directory + ": cannot write there (" + (reason ? std::strerror(reason) : std::string("write failed")) +
                     "); choose another -o or free some space");
}

}  // namespace tessera

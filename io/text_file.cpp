#include "io/text_file.h"

#include "io/input_error.h"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace tessera {

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
    throw InputError(path + ": cannot be read; check that it exists and may be read");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": cannot be read to its end (an I/O error)");
  return text;
}

}  // namespace tessera

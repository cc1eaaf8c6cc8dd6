#pragma once
#include <string>

namespace tessera {

/// The whole of a file, byte for byte. Throws InputError naming the file when it cannot be opened
/// or read (missing, a folder, no permission).
std::string readTextFile(const std::string& path);

}  // namespace tessera

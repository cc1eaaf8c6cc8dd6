#pragma once
#include <string>

namespace tessera {

/// Checks, before any work, that `directory` is or can be made a directory this process can write:
/// creates it (and its parents) and a probe file, then removes what it made. InputError naming the
/// path and the reason ("not a directory", "not writable", "no space left") otherwise.
void requireWritableDirectory(const std::string& directory);

}  // namespace tessera

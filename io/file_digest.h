#pragma once
#include <string>

namespace tessera {

/// A 64-bit FNV-1a digest of a text or of a file's bytes, as 16 hex digits: enough to tell that a
/// file changed (not a cryptographic hash). fileDigest throws InputError if the file cannot be read.
/// Source: Fowler, Noll, Vo, "FNV hash" (IETF draft-eastlake-fnv), 64-bit offset basis and prime.
std::string textDigest(const std::string& text);
std::string fileDigest(const std::string& path);

}  // namespace tessera

#include "io/file_digest.h"

#include "io/input_error.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

namespace tessera {

namespace {

constexpr std::uint64_t kOffsetBasis = 14695981039346656037ull;
constexpr std::uint64_t kPrime = 1099511628211ull;

void mix(std::uint64_t& h, const char* bytes, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(bytes[i]);
    h *= kPrime;
  }
}

std::string hex(std::uint64_t h) {
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

}  // namespace

std::string textDigest(const std::string& text) {
  std::uint64_t h = kOffsetBasis;
  mix(h, text.data(), text.size());
  return hex(h);
}

std::string fileDigest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read it");
  std::uint64_t h = kOffsetBasis;
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    mix(h, buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(path + ": cannot read it");
  return hex(h);
}

}  // namespace tessera

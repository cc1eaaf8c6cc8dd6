// Safe writes (a file is whole or absent) and file digests.
#include "io/file_digest.h"
#include "io/input_error.h"
#include "io/safe_write.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

using namespace tessera;
namespace fs = std::filesystem;

namespace {
std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}
}  // namespace

TEST_CASE("FNV-1a 64 digests match the published test vectors") {
  // Fowler-Noll-Vo test vectors (IETF draft-eastlake-fnv): "" and "a".
  REQUIRE(textDigest("") == "cbf29ce484222325");
  REQUIRE(textDigest("a") == "af63dc4c8601ec8c");
  REQUIRE(textDigest("foobar") == "85944171f73967e8");
  test::TempDir dir;
  test::writeFile(dir / "f", "foobar");
  REQUIRE(fileDigest(dir / "f") == textDigest("foobar"));
  REQUIRE_THROWS_AS(fileDigest(dir / "missing"), InputError);
}

TEST_CASE("a failed safe write leaves the previous file whole and no temporary behind") {
  test::TempDir dir;
  const fs::path target = dir.path() / "result.txt";
  writeTextFileSafely(target, "first");
  REQUIRE(read(target) == "first");
  REQUIRE_THROWS_AS(writeFileSafely(target,
                                    [](const fs::path& p) {
                                      std::ofstream(p) << "half of the second";
                                      throw std::runtime_error("the writer failed");
                                    }),
                    WriteError);
  REQUIRE(read(target) == "first");
  REQUIRE(entries(dir.path()) == 1);
  // A check that fails after writing counts as a failed write too.
  REQUIRE_THROWS_WITH(writeFileSafely(
                          target, [](const fs::path& p) { std::ofstream(p) << "second"; },
                          [](const fs::path&) { throw std::runtime_error("does not read back"); }),
                      Catch::Contains("result.txt: cannot write") && Catch::Contains("does not read back"));
  REQUIRE(read(target) == "first");
  writeTextFileSafely(target, "second");
  REQUIRE(read(target) == "second");
}

TEST_CASE("temporaries of killed writers are removed, a live writer's are kept") {
  test::TempDir dir;
  pid_t gone = 4194303;  // above any pid in use here, checked below
  while (::kill(gone, 0) == 0) --gone;
  test::writeFile(dir / (".tmp-" + std::to_string(gone) + "-bundle.h5"), "stale");
  test::writeFile(dir / (".tmp-" + std::to_string(::getpid()) + "-other.h5"), "being written");
  test::writeFile(dir / ".tmp-notapid-x", "not ours");
  writeTextFileSafely(dir.path() / "new.txt", "x");
  REQUIRE_FALSE(fs::exists(dir / (".tmp-" + std::to_string(gone) + "-bundle.h5")));
  REQUIRE(fs::exists(dir / (".tmp-" + std::to_string(::getpid()) + "-other.h5")));
  REQUIRE(fs::exists(dir / ".tmp-notapid-x"));
}

TEST_CASE("writing into a folder that is not writable is a WriteError naming the file") {
  test::TempDir dir;
  REQUIRE_THROWS_WITH(writeTextFileSafely(dir.path() / "no-such-folder" / "f.txt", "x"),
                      Catch::Contains("f.txt: cannot write"));
}

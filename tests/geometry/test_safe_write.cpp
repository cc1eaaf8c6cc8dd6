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
  REQUIRE(test::readFile(target) == "first");
  REQUIRE_THROWS_AS(writeFileSafely(target,
                                    [](const fs::path& p) {
                                      std::ofstream(p) << "half of the second";
                                      throw std::runtime_error("the writer failed");
                                    }),
                    WriteError);
  REQUIRE(test::readFile(target) == "first");
  REQUIRE(entries(dir.path()) == 1);
  // A check that fails after writing counts as a failed write too.
  REQUIRE_THROWS_WITH(writeFileSafely(
                          target, [](const fs::path& p) { std::ofstream(p) << "second"; },
                          [](const fs::path&) { throw std::runtime_error("does not read back"); }),
                      Catch::Contains("result.txt: cannot write") && Catch::Contains("does not read back"));
  REQUIRE(test::readFile(target) == "first");
  writeTextFileSafely(target, "second");
  REQUIRE(test::readFile(target) == "second");
}

TEST_CASE("temporaries of killed writers are removed, a live writer's and another machine's are kept") {
  test::TempDir dir;
  pid_t gone = 4194303;  // above any pid in use here, checked below
  while (::kill(gone, 0) == 0) --gone;
  char hostName[256] = {};
  REQUIRE(::gethostname(hostName, sizeof hostName - 1) == 0);
  const std::string host = textDigest(hostName[0] != '\0' ? hostName : "localhost").substr(0, 8);
  const auto temporary = [&](pid_t pid, const std::string& on, const std::string& name) {
    return dir / (".tmp-" + std::to_string(pid) + "@" + on + "@" + name);
  };
  const fs::path stale = temporary(gone, host, "bundle.h5"), live = temporary(::getpid(), host, "other.h5"),
                 elsewhere = temporary(gone, host + "-node7", "sweep.csv"), before = dir / (".tmp-" + std::to_string(gone) + "-old.h5");
  for (const fs::path& p : {stale, live, elsewhere, before}) test::writeFile(p, "x");
  test::writeFile(dir / ".tmp-notapid-x", "not ours");
  test::writeFile(dir / ".tmp-99999999999999999999-x", "no pid has this many digits");
  writeTextFileSafely(dir.path() / "new.txt", "x");
  REQUIRE_FALSE(fs::exists(stale));
  REQUIRE_FALSE(fs::exists(before));  // the form before the host was written: this machine's
  REQUIRE(fs::exists(live));
  REQUIRE(fs::exists(elsewhere));  // a pid of another machine says nothing here
  REQUIRE(fs::exists(dir / ".tmp-notapid-x"));
  REQUIRE(fs::exists(dir / ".tmp-99999999999999999999-x"));
}

TEST_CASE("a temporary carries its writer's pid and this machine's name's digest") {
  test::TempDir dir;
  char hostName[256] = {};
  REQUIRE(::gethostname(hostName, sizeof hostName - 1) == 0);
  const std::string expected =
      ".tmp-" + std::to_string(::getpid()) + "@" + textDigest(hostName[0] != '\0' ? hostName : "localhost").substr(0, 8) + "@out.txt";
  std::string seen;
  writeFileSafely(dir.path() / "out.txt", [&](const fs::path& p) {
    seen = p.filename().string();
    std::ofstream(p) << "x";
  });
  REQUIRE(seen == expected);
  REQUIRE(test::readFile(dir.path() / "out.txt") == "x");
}

TEST_CASE("writing into a folder that is not writable is a WriteError naming the file") {
  test::TempDir dir;
  REQUIRE_THROWS_WITH(writeTextFileSafely(dir.path() / "no-such-folder" / "f.txt", "x"),
                      Catch::Contains("f.txt: cannot write"));
}

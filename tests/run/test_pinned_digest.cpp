// Answers change only on purpose: a short run's final state, digested to the last bit, against the
// digest pinned for this compiler and CPU version (the explicit step's SIMD loops and the implicit
// evaluation are compiled for the baseline CPU, AVX2 and AVX-512, and fused multiply-adds round
// differently: solver/cpu_versions.h). A
// change to the physics, the protocol or the order of a sum changes it: pin the new digest the
// failure prints, and say in the commit why the answers moved. Where no digest is pinned (another
// compiler or CPU) the test says so and passes.
#include "run/run_session.h"
#include "run/state_digest.h"
#include "tests/fixtures/scenes.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <map>
#include <string>

using namespace tessera;

namespace {

// The CPU version the dispatcher of TESSERA_CPU_VERSIONS picks here, as GCC names it.
std::string cpuVersion() {
#if defined(TESSERA_PORTABLE)
  return "portable";
#elif defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return "x86-64-v4";
  if (__builtin_cpu_supports("x86-64-v3")) return "x86-64-v3";
  return "x86-64";
#else
  return "";
#endif
}

// The compiler and whether it optimised (GCC fuses multiply-adds only when it does).
std::string compiler() {
#if defined(__OPTIMIZE__)
  const std::string optimised;
#else
  const std::string optimised = " unoptimised";
#endif
#if defined(__clang__)
  return std::string("clang ") + __clang_version__ + optimised;
#elif defined(__GNUC__)
  return std::string("gcc ") + __VERSION__ + optimised;
#else
  return "";
#endif
}

// The 3 x 3 slab of the default block loaded to 0.3 mm on one thread, by `method`.
std::string runDigest(const std::string& method) {
  test::TempDir dir;
  writeBundle(dir / "slab", test::smallSlab(3, 0.25e-3, 1.0e-3));
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nradius = 2.5e-3\nspeed = 0.03\n[protocol]\ndelta_max = 0.3e-3\n"
                                      "[damping]\nlocal = 0.3\n[solver]\nmethod = \"" + method + "\"\n");
  RunRequest r;
  r.scene = dir / "scene.toml";
  r.threads = 1;
  auto session = RunSession::start(r, {});
  session->run({});
  REQUIRE(session->record().stopReason == StopReason::DeltaMax);
  return stateDigest(session->world());
}

}  // namespace

TEST_CASE("pinned digests: a short run ends in the state pinned for this compiler and CPU version, by either method") {
  // compiler, CPU version, method -> digest
  const std::map<std::string, std::string> pinned{
      {"gcc 12.2.0 x86-64-v4 explicit", "b3fc47b24e8c45a1"},
      {"gcc 12.2.0 x86-64-v4 implicit", "77ab4f1e546334a5"},
  };
  for (const std::string method : {"explicit", "implicit"}) {
    const std::string key = compiler() + " " + cpuVersion() + " " + method;
    const std::string digest = runDigest(method);
    const auto found = pinned.find(key);
    if (found == pinned.end()) {
      WARN("no digest pinned for '" << key << "' (this run's: " << digest << "): add it to tests/run/test_pinned_digest.cpp");
      continue;
    }
    INFO("'" << key << "': this run's digest is " << digest << "; if the answers moved on purpose, pin it in tests/run/test_pinned_digest.cpp");
    CHECK(digest == found->second);
  }
}

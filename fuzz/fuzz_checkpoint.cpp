// Fuzz target: the checkpoint reader and the World's check of a restored state, on a two-block
// stack, the indenter pressing on it: the world's state and a loading run's protocol state (phase,
// first contact, sampling, curve). A damaged checkpoint must be an InputError (or the World's
// refusal), never a crash.
// `fuzz_checkpoint --seeds DIR` writes the seeds: DIR/bundle/stack.h5 and DIR/checkpoint/stack.h5.
#include "fuzz/input_file.h"
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "levelset/bundle.h"
#include "levelset/shape_builder.h"
#include "run/checkpoint.h"
#include "solver/world.h"

#include <cstring>
#include <filesystem>
#include <memory>

namespace {

tessera::Bundle makeStack() {
  tessera::ShapeResolution r;
  r.voxelSize = 1.0e-3;
  r.nodeSpacing = 2.5e-3;
  tessera::PrepLog log;
  tessera::Bundle b;
  b.shapes.push_back(tessera::buildShape("block", tessera::makeBox(10e-3, 10e-3, 3e-3), {}, r, "block", log));
  tessera::Body base, top;
  base.name = "base";
  base.fixed = true;
  top.name = "top";
  top.position = Eigen::Vector3d(0, 0, 3e-3);
  b.bodies = {base, top};
  b.spanLength = 10e-3;
  b.spanInterfaces = 2;
  return b;
}

const tessera::Bundle& stack() {
  static const tessera::Bundle bundle = makeStack();
  return bundle;
}

tessera::World& world() {
  static const tessera::Bundle bundle = stack();
  static tessera::World w(bundle.shapes, bundle.bodies, tessera::ContactParameters{}, tessera::SolverSettings{});
  return w;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  if (*argc == 3 && std::strcmp((*argv)[1], "--seeds") == 0) {
    namespace fs = std::filesystem;
    const fs::path dir = (*argv)[2];
    const fs::path bundleDir = fs::temp_directory_path() / "tessera-fuzz-seed-bundle";
    tessera::writeBundle(bundleDir.string(), stack());
    fs::create_directories(dir / "bundle");
    fs::create_directories(dir / "checkpoint");
    fs::copy_file(bundleDir / "bundle.h5", dir / "bundle/stack.h5", fs::copy_options::overwrite_existing);
    fs::remove_all(bundleDir);
    tessera::World& w = world();
    tessera::SphereObstacle indenter;  // pressing on the top block: a loading run's protocol state
    indenter.center = Eigen::Vector3d(0, 0, 4.5e-3 + indenter.radius - 1e-6);
    indenter.velocity = Eigen::Vector3d(0, 0, -0.01);
    w.addSphere(indenter);
    for (int i = 0; i < 200; ++i) w.step();  // springs and pairs to read back
    tessera::IndentationState state;
    tessera::IndentationRecord record;
    state.phase = 1;
    state.sphere = 0;
    state.contactTravel = state.contactPath = 1e-6;
    state.peak = 2.0;
    state.nextSample = state.nextSnapshot = 2e-6;
    state.settledPosition = w.bodies().position;
    state.outAt.assign(w.bodies().size(), -1.0);
    record.target = 1;
    record.targetName = "top";
    record.thickness = 3e-3;
    record.deltaMax = 1e-3;
    record.timeStep = w.timeStep();
    for (int k = 0; k < 3; ++k) {
      tessera::CurveSample c;
      c.time = c.delta = 1e-6 * k;
      c.load = 1.0 * k;
      record.curve.push_back(c);
    }
    tessera::writeCheckpoint((dir / "checkpoint/stack.h5").string(), {}, w.state(), state, record);
    std::exit(0);
  }
  world();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tessera::fuzz::writeInput(data, size, ".h5");
  try {
    tessera::readCheckpointSource(path);
    tessera::WorldState s = world().state();
    tessera::IndentationState state;
    tessera::IndentationRecord record;
    tessera::readCheckpoint(path, s, state, record);
    world().checkState(s);
  } catch (const tessera::InputError&) {
  } catch (const std::invalid_argument&) {  // the World's refusal of a state
  }
  return 0;
}

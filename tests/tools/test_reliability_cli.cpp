// Reliability (issue: never lose, corrupt or mislabel a result): each test is named after the
// defect it guards against.
#include "io/file_digest.h"
#include "levelset/bundle.h"
#include "io/hdf5_file.h"
#include "tests/fixtures/temp_dir.h"
#include "tests/tools/cli_runner.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>

using namespace tessera;
using tessera::test::kDefaultBlock;
using tessera::test::quoted;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

std::string tile(const fs::path& out, const std::string& extra = "") {
  return "tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 3x3 --pitch 10 --spacing 1.0 -o " + quoted(out) + extra;
}

}  // namespace

TEST_CASE("reliability 6: tile refuses to replace an existing bundle without --replace") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  const auto before = fs::last_write_time(dir / "slab/bundle.h5");
  const test::CliResult again = test::runTessera(tile(dir / "slab"));
  REQUIRE(again.status == 2);
  REQUIRE_THAT(again.err, Contains("holds a bundle already") && Contains("--replace"));
  REQUIRE(fs::last_write_time(dir / "slab/bundle.h5") == before);
  REQUIRE(test::runTessera(tile(dir / "slab", " --replace")).status == 0);
}

TEST_CASE("reliability 7: output paths are checked before any work") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[protocol]\ndelta_max = 0.2e-3\n");
  test::writeFile(dir / "a_file", "x");
  const struct {
    std::string output, expected;
  } cases[] = {
      {dir / "a_file", "exists and is not a directory"},
      {dir / "a_file/below", "cannot create the output directory"},
      {"/proc/tessera-out", "cannot"},
      {dir / "slab", "is the bundle's folder"},
  };
  for (const auto& c : cases) {
    const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(c.output));
    INFO(c.output << ": " << r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains(c.expected));
    REQUIRE_THAT(r.err, !Contains("internal error"));
    REQUIRE_THAT(r.err, !Contains("run: delta"));  // refused before the run began
  }
  REQUIRE_FALSE(fs::exists(dir / "slab/summary.json"));
  const test::CliResult tileToFile = test::runTessera(tile(dir / "a_file"));
  REQUIRE(tileToFile.status == 2);
  REQUIRE_THAT(tileToFile.err, Contains("not a directory"));
}

TEST_CASE("reliability 10: command-line mistakes exit 2, help exits 0") {
  const test::CliResult unknown = test::runTessera("run --no-such-flag");
  REQUIRE(unknown.status == 2);
  const test::CliResult missing = test::runTessera("prep");
  REQUIRE(missing.status == 2);
  const test::CliResult notANumber = test::runTessera("tile --block x.obj --unit mm --pitch 20mm -o y");
  REQUIRE(notANumber.status == 2);
  // One line: what was wrong, and how to give it.
  REQUIRE_THAT(notANumber.err, Contains("tessera: error: ") && Contains("--pitch") && Contains("give a plain number") &&
                                   Contains("see tessera tile --help"));
  REQUIRE(std::count(notANumber.err.begin(), notANumber.err.end(), '\n') == 1);
  REQUIRE(test::runTessera("run --help").status == 0);
  REQUIRE(test::runTessera("--version").status == 0);
}

TEST_CASE("reliability 12: nonsense run options are refused: negative threads") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --threads -3 -o " + quoted(dir / "out"));
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("--threads"));
  REQUIRE_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("reliability 2: a sweep re-run with other values is refused, not relabelled") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 0.05e-3\n");
  const std::string sweep = "sweep " + quoted(dir / "scene.toml") + " -o " + quoted(dir / "mu") + " --jobs 2 --set mu=";
  REQUIRE(test::runTessera(sweep + "0.2,0.3").status == 0);
  const test::CliResult other = test::runTessera(sweep + "0.8,0.9");
  REQUIRE(other.status == 2);
  REQUIRE_THAT(other.err, Contains("holds a sweep of other values") && Contains("material.friction = 0.8") &&
                             Contains("--extend"));
  const std::string text = test::readFile(dir / "mu/case_000/scene.toml");
  REQUIRE_THAT(text, Contains("friction = 0.2"));
  // The same sweep again finishes what is missing (here: nothing).
  const test::CliResult same = test::runTessera(sweep + "0.2,0.3");
  REQUIRE(same.status == 0);
  REQUIRE_THAT(same.err, Contains("already complete"));
  // Told to extend, it adds the new values as new cases and tables all four.
  const test::CliResult extended = test::runTessera(sweep + "0.3,0.8 --extend");
  INFO(extended.err);
  REQUIRE(extended.status == 0);
  REQUIRE_THAT(extended.err, Contains("case_001 already complete") && Contains("running case_002"));
  REQUIRE_THAT(extended.out, Contains("3 of 3 cases"));
  // Another base scene for a value the folder holds: refused, naming the case.
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nspeed = 0.06\n[protocol]\ndelta_max = 0.05e-3\n");
  const test::CliResult otherBase = test::runTessera(sweep + "0.2");
  REQUIRE(otherBase.status == 2);
  REQUIRE_THAT(otherBase.err, Contains("case_000 holds the case material.friction = 0.2 of another base scene"));
  const test::CliResult otherBaseNewValue = test::runTessera(sweep + "0.9 --extend");
  REQUIRE(otherBaseNewValue.status == 2);
  REQUIRE_THAT(otherBaseNewValue.err, Contains("holds a sweep of another base scene or preset"));
}

TEST_CASE("reliability 5: run refuses a bundle whose bodies overlap, coincident ones included") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  Bundle edited = readBundle(dir / "slab");
  edited.bodies[3].position = edited.bodies[4].position;  // r1c0 moved onto the centre block
  edited.bodies[3].orientation = edited.bodies[4].orientation;
  writeBundle(dir / "edited", edited);
  test::writeFile(dir / "scene.toml", "bundle = \"edited\"\n[protocol]\ndelta_max = 0.1e-3\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "out"));
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("'r1c0' and 'r1c1' overlap") || Contains("'r1c1' and 'r1c0' overlap"));
  REQUIRE_FALSE(fs::exists(dir / "out"));
}

namespace {

// A finished 3 x 3 run in dir/run (its checkpoint kept), from dir/scene.toml on dir/slab.
void finishedRun(const test::TempDir& dir) {
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 0.2e-3\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "run"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE(fs::exists(dir / "run/checkpoint.h5"));
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().rfind(".tmp-", 0) == 0 || (e.is_regular_file() && e.file_size() == 0 &&
                                                                e.path().filename() != ".lock"))
      found.push_back(e.path().string());
  return found;
}

// Replaces dataset `name` of group `group` in an HDF5 file.
template <class T>
void replaceDataset(const std::string& file, const std::string& group, const std::string& name, const std::vector<T>& values,
                    const std::vector<hsize_t>& dims) {
  h5::Handle f(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  REQUIRE(f.valid());
  h5::Handle g = h5::openGroup(f.get(), group);
  REQUIRE(H5Ldelete(g.get(), name.c_str(), H5P_DEFAULT) >= 0);
  h5::writeDataset(g.get(), name, values, dims);
}

template <class T>
void replaceAttribute(const std::string& file, const std::string& group, const std::string& name, const T& value) {
  h5::Handle f(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  REQUIRE(f.valid());
  h5::Handle g = group.empty() ? h5::Handle(H5Oopen(f.get(), "/", H5P_DEFAULT)) : h5::openGroup(f.get(), group);
  REQUIRE(H5Adelete(g.get(), name.c_str()) >= 0);
  h5::writeAttribute(g.get(), name, value);
}

}  // namespace

TEST_CASE("reliability 1: a full disk is one clear error, exit 2, and the previous files stay whole") {
  test::TempDir dir;
  finishedRun(dir);
  const std::string bundleBefore = fileDigest(dir / "slab/bundle.h5");
  const std::string smallDisk = "ulimit -f 60; trap '' XFSZ;";  // files of at most 60 KiB: "File too large"
  const test::CliResult retile = test::runTessera(tile(dir / "slab", " --replace"), smallDisk);
  INFO(retile.err);
  REQUIRE(retile.status == 2);
  REQUIRE_THAT(retile.err, Contains("cannot write: disk full"));
  REQUIRE(fileDigest(dir / "slab/bundle.h5") == bundleBefore);
  REQUIRE(temporaries(dir / "slab").empty());

  const test::CliResult run = test::runTessera(
      "run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "full"), "ulimit -f 40; trap '' XFSZ;");
  INFO(run.err);
  REQUIRE(run.status == 2);  // not 139: no crash in the HDF5 library's exit handlers
  REQUIRE_THAT(run.err, Contains("checkpoint.h5: cannot write: disk full"));
  REQUIRE(temporaries(dir / "full").empty());
  REQUIRE_FALSE(fs::exists(dir / "full/summary.json"));
}

TEST_CASE("reliability 3: a damaged checkpoint is one clear error, never a crash") {
  test::TempDir dir;
  finishedRun(dir);
  const std::string checkpoint = dir / "run/checkpoint.h5";
  fs::copy_file(checkpoint, dir / "good.h5");
  const auto refused = [&](const std::string& damage) {
    const test::CliResult r = test::runTessera("run --resume " + quoted(dir / "run") + " --no-plot");
    INFO(damage << ": " << r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains("checkpoint.h5") && (Contains("corrupt checkpoint") || Contains("cannot resume")));
    REQUIRE_THAT(r.err, Contains("start the run again from its scene"));  // the fix, every time
    fs::copy_file(dir / "good.h5", checkpoint, fs::copy_options::overwrite_existing);
  };
  std::vector<hsize_t> dims;
  const auto pairA = [&] {
    h5::Handle f = h5::openFileReadOnly(checkpoint);
    return h5::readDataset<std::int32_t>(h5::openGroup(f.get(), "world").get(), "pair_a", &dims);
  }();
  REQUIRE_FALSE(pairA.empty());
  replaceDataset(checkpoint, "world", "pair_a", std::vector<std::int32_t>(pairA.size(), 999), dims);
  refused("pair index out of range");
  replaceDataset(checkpoint, "world", "pair_a", std::vector<std::int32_t>(pairA.size(), -7), dims);
  refused("negative pair index");
  replaceDataset(checkpoint, "world", "pair_contacts", std::vector<std::int32_t>(pairA.size(), -5), dims);
  refused("negative contact count");
  replaceDataset(checkpoint, "world", "pair_contacts", std::vector<std::int32_t>(pairA.size(), 1 << 30), dims);
  refused("huge contact count");
  replaceDataset(checkpoint, "world", "contact_key", std::vector<double>{}, {0});
  refused("no contact keys");
  replaceDataset(checkpoint, "world", "orientation", std::vector<double>(36, std::nan("")), {9, 4});
  refused("NaN orientation");
  const auto offsets = [&] {
    h5::Handle f = h5::openFileReadOnly(checkpoint);
    return h5::readDataset<std::int32_t>(h5::openGroup(f.get(), "run/snapshots").get(), "force_offset", &dims);
  }();
  std::vector<std::int32_t> huge = offsets;
  huge.back() = 1 << 30;
  replaceDataset(checkpoint, "run/snapshots", "force_offset", huge, dims);
  refused("huge contact-record count");
  std::vector<std::int32_t> falling = offsets;
  falling.back() = -1;
  replaceDataset(checkpoint, "run/snapshots", "force_offset", falling, dims);
  refused("decreasing contact-record offsets");
  // The protocol's state (issue #39): each value against what the protocol can have made of it.
  const double nan = std::nan("");
  for (const char* name : {"delta_max", "next_sample", "contact_travel", "peak", "load_start"}) {
    replaceAttribute(checkpoint, "run", name, nan);
    refused(std::string(name) + " NaN");
  }
  replaceAttribute(checkpoint, "run", "thickness", 0.0);
  refused("zero thickness");
  replaceAttribute(checkpoint, "run", "target", std::int64_t{0});  // r0c0, a fixed corner block
  refused("the target moved to a fixed body");
  const auto loads = [&] {
    h5::Handle f = h5::openFileReadOnly(checkpoint);
    return h5::readDataset<double>(h5::openGroup(f.get(), "run/curve").get(), "load", &dims);
  }();
  REQUIRE(loads.size() > 2);
  std::vector<double> nanLoad = loads;
  nanLoad[1] = nan;
  replaceDataset(checkpoint, "run/curve", "load", nanLoad, dims);
  refused("a NaN load in the curve");
  {
    h5::Handle f(H5Fopen(checkpoint.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
    h5::Handle curve = h5::openGroup(f.get(), "run/curve");
    for (const std::string& column : h5::childNames(curve.get())) {
      REQUIRE(H5Ldelete(curve.get(), column.c_str(), H5P_DEFAULT) >= 0);
      h5::writeDataset(curve.get(), column, std::vector<double>{}, {0});
    }
  }
  refused("an emptied curve");
  replaceAttribute(checkpoint, "", "scene_text", std::string("bundle = \"slab\"\n[protocol]\ndelta_max = 0.9e-3\n"));
  refused("an edited scene text");
  test::writeFile(checkpoint, "not HDF5 at all");
  refused("garbage");
  // Undamaged, it resumes.
  REQUIRE(test::runTessera("run --resume " + quoted(dir / "run") + " --no-plot").status == 0);
}

TEST_CASE("reliability 4a: a finished run resumed is left as it is, and a resume elsewhere is refused") {
  test::TempDir dir;
  finishedRun(dir);
  const std::string summary = fileDigest(dir / "run/summary.json"), results = fileDigest(dir / "run/results.h5");
  test::CliResult r = test::runTessera("run --resume " + quoted(dir / "run"));  // without --no-plot: still no plots
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("is complete (stopped: delta_max") && Contains("nothing to resume"));
  REQUIRE(fileDigest(dir / "run/summary.json") == summary);
  REQUIRE(fileDigest(dir / "run/results.h5") == results);
  REQUIRE_FALSE(fs::exists(dir / "run/curve.png"));
  // -o names another folder: refused, nothing made there.
  r = test::runTessera("run --resume " + quoted(dir / "run") + " --no-plot -o " + quoted(dir / "other"));
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("a run resumes in its own folder"));
  REQUIRE_FALSE(fs::exists(dir / "other"));
  REQUIRE(test::runTessera("run --resume " + quoted(dir / "run") + " --no-plot -o " + quoted(dir / "run")).status == 0);
  // Its last write cut short (a full disk, a kill): summary.json, written last, is still the one of
  // an earlier checkpoint ("running"). Resuming writes the results again.
  {
    std::string text = test::readFile(dir / "run/summary.json");
    const std::string final = "\"stop_reason\": \"delta_max\"";
    REQUIRE(text.find(final) != std::string::npos);
    text.replace(text.find(final), final.size(), "\"stop_reason\": \"running\"");
    test::writeFile(dir / "run/summary.json", text);
  }
  r = test::runTessera("run --resume " + quoted(dir / "run") + " --no-plot");
  REQUIRE(r.status == 0);
  const std::string text = test::readFile(dir / "run/summary.json");
  REQUIRE_THAT(text, Contains("\"stop_reason\": \"delta_max\""));
}

TEST_CASE("reliability 4: resume refuses a changed scene, bundle or preset, and finds a run folder moved with its bundle") {
  test::TempDir dir;
  finishedRun(dir);
  const std::string resume = "run --resume " + quoted(dir / "run") + " --no-plot";
  const std::string sceneText = "bundle = \"slab\"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 0.2e-3\n";
  test::writeFile(dir / "scene.toml", sceneText + "[material]\nfriction = 0.9\n");
  test::CliResult r = test::runTessera(resume);
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("scene.toml: changed since the run"));
  test::writeFile(dir / "scene.toml", sceneText);
  r = test::runTessera(resume + " --preset fast");
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("this run started without --preset"));

  // Moved together, the run folder finds its bundle beside it and resumes from its own scene.
  fs::create_directories(dir / "moved");
  fs::copy(dir / "run", dir / "moved/run", fs::copy_options::recursive);
  fs::copy(dir / "slab", dir / "moved/slab", fs::copy_options::recursive);
  fs::remove(dir / "scene.toml");
  r = test::runTessera("run --resume " + quoted(dir / "moved/run") + " --no-plot");
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("is complete"));  // found its bundle and scene; it had finished

  REQUIRE(test::runTessera(tile(dir / "slab", " --replace --gap 0.01")).status == 0);
  r = test::runTessera(resume);
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("not the bundle the run in") && Contains("re-tiled or edited"));
}

TEST_CASE("reliability 9: limits are refused with the number and the fix") {
  test::TempDir dir;
  const struct {
    std::string arguments, expected;
  } cases[] = {
      {tile(dir / "a", "").replace(tile(dir / "a", "").find("3x3"), 3, "1000x1000"), "more than --max-bodies 10000"},
      {tile(dir / "a", "").replace(tile(dir / "a", "").find("3x3"), 3, "99999999999x3"), "more than --max-bodies"},
      {"block wave --unit mm --levels 10000000 -o " + quoted(dir / "w.obj"), "at most 1000 --waves and 10000 --levels"},
      {"tile --layout " + quoted(TESSERA_ASSETS "/layouts/hex_slab.json") + " --max-bodies 5 -o " + quoted(dir / "h"),
       "bodies, more than --max-bodies 5"},
  };
  for (const auto& c : cases) {
    const test::CliResult r = test::runTessera(c.arguments);
    INFO(c.arguments << ": " << r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains(c.expected));
  }
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  const auto runRefused = [&](const std::string& scene, const std::string& expected) {
    test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n" + scene);
    const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "out"));
    INFO(scene << ": " << r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains(expected));
    REQUIRE_FALSE(fs::exists(dir / "out"));
  };
  runRefused("[solver]\ntime_step = 1e-300\n", "below 1e-4 of the stability estimate");
  runRefused("[solver]\ngravity = [0, 0, -1e300]\n", "gravity must be at most 1000 m/s^2");
  runRefused("[material]\nfriction = inf\n", "must be a finite number (Coulomb coefficient), got inf");
  const test::CliResult sweep = test::runTessera("sweep " + quoted(dir / "scene.toml") + " -o " + quoted(dir / "many") +
                                                 " --set mu=0.1:0.5:1000000");
  REQUIRE(sweep.status == 2);
  REQUIRE_THAT(sweep.err, Contains("more than --max-cases 1000"));
  REQUIRE_FALSE(fs::exists(dir / "many"));
}

TEST_CASE("reliability 11: values inside a bundle are checked: a corrupt bundle is one clear error") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  const Bundle good = readBundle(dir / "slab");
  const double nan = std::nan("");
  const struct {
    std::function<void(Bundle&)> damage;
    std::string expected;
  } cases[] = {
      {[&](Bundle& b) { b.shapes[0].nodes.positions[3].x() = nan; }, "node 3 has a non-finite position"},
      {[&](Bundle& b) { b.shapes[0].nodes.areas[5] = 0; }, "node 5 has a zero, negative or non-finite area"},
      {[&](Bundle& b) { b.shapes[0].nodes.normals[2].setZero(); }, "node 2 has a normal that is not a unit vector"},
      {[&](Bundle& b) { b.shapes[0].sdf.origin.y() = nan; }, "the grid's origin or voxel size"},
      {[&](Bundle& b) { b.shapes[0].nodes = SurfaceNodes{}; }, "fewer than 4 surface nodes"},
      {[&](Bundle& b) { b.bodies[2].name = b.bodies[1].name; }, "a second body of that name"},
      {[&](Bundle& b) { b.bodies[4].orientation.coeffs()[0] = nan; }, "its orientation is not a unit quaternion"},
      {[&](Bundle& b) { b.bodies[0].position.z() = std::numeric_limits<double>::infinity(); }, "its position is not finite"},
      // What prep derives from the mesh, recomputed from it (issue #39).
      {[&](Bundle& b) { b.shapes[0].mesh.triangles.pop_back(); }, "the mesh is open"},
      {[&](Bundle& b) { b.shapes[0].mesh.triangles[0][1] = b.shapes[0].mesh.triangles[0][0]; }, "has zero area"},
      {[&](Bundle& b) { b.shapes[0].mass.volume = 1e300; }, "a volume or surface area that is not its mesh's"},
      {[&](Bundle& b) { b.shapes[0].mass.principalMoments[1] *= 2; }, "principal moments that are not its mesh's"},
      {[&](Bundle& b) { b.shapes[0].mass.principalAxes(0, 1) = nan; }, "principal axes"},
      {[&](Bundle& b) { b.shapes[0].mass.centroid.x() = nan; }, "a centroid"},
      {[&](Bundle& b) { b.shapes[0].nodes.positions[7].x() += 1.0; }, "node 7 is off the mesh's surface"},
      {[&](Bundle& b) { b.shapes[0].nodes.areas[5] = 1e300; }, "node areas that do not sum"},
      {[&](Bundle& b) { b.shapes[0].resolution.voxelSize = 0; }, "a voxel size or node spacing"},
      {[&](Bundle& b) { b.shapes[0].sdf.voxelSize = nan; }, "positive voxel size"},
  };
  for (const auto& c : cases) {
    Bundle bad = good;
    c.damage(bad);
    fs::remove_all(dir / "bad");
    writeBundle(dir / "bad", bad);
    for (const std::string command : {"inspect ", "export "}) {
      const test::CliResult r =
          test::runTessera(command + quoted(dir / "bad") + (command == "export " ? " -o " + quoted(dir / "view") : ""));
      INFO(command << c.expected << ": " << r.err);
      REQUIRE(r.status == 2);
      REQUIRE_THAT(r.err, Contains("corrupt or incomplete bundle") && Contains(c.expected));
    }
  }
  // A count stored as a number with a fraction is not read as its integer part.
  fs::remove_all(dir / "bad");
  writeBundle(dir / "bad", good);
  replaceAttribute(dir / "bad/bundle.h5", "bodies", "span_interfaces", 2.5);
  const test::CliResult span = test::runTessera("inspect " + quoted(dir / "bad"));
  REQUIRE(span.status == 2);
  REQUIRE_THAT(span.err, Contains("corrupt or incomplete bundle") && Contains("'span_interfaces' is not an integer"));
}

TEST_CASE("reliability 13: a second writer of a run folder is refused while the first holds it") {
  test::TempDir dir;
  finishedRun(dir);
  // flock(1) holds the folder's lock as a running tessera would.
  const std::string holder = "(flock " + quoted(dir / "run/.lock") + " sleep 3 &); sleep 0.5;";
  const test::CliResult r = test::runTessera("run --resume " + quoted(dir / "run") + " --no-plot", holder);
  INFO(r.err);
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("another tessera process") && Contains("is writing a run there"));
}

TEST_CASE("reliability 14: messages say what happened") {
  test::TempDir dir;
  finishedRun(dir);
  const test::CliResult noPlot = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "b"));
  REQUIRE(noPlot.status == 0);
  REQUIRE_THAT(noPlot.out, Contains("written to") && !Contains("curve.png"));
  const test::CliResult report = test::runTessera("report " + quoted(dir / "run"));
  REQUIRE(report.status == 2);
  REQUIRE_THAT(report.err, Contains("not a sweep folder") && !Contains("Traceback"));
}

// The run of one scene in process (run/run_session.h): checkpoint round trips, the sample hook
// steering the indenter, presets and overrides, determinism across thread counts.
#include "io/hdf5_file.h"
#include "io/input_error.h"
#include "run/curve_table.h"
#include "run/presets.h"
#include "run/run_session.h"
#include "run/state_digest.h"
#include "tests/fixtures/bit_flips.h"
#include "tests/fixtures/scenes.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

// A 3 x 3 slab of the default block and the default scene on it, loaded to 0.6 mm (n x n and
// another delta_max, `solver` the text of a [solver] table, `indenter` more [indenter] keys, if
// given; `material` more [material] keys).
struct SmallTest {
  test::TempDir dir;
  std::string scene = dir / "scene.toml";
  explicit SmallTest(int n = 3, double deltaMax = 0.6e-3, const std::string& solver = "", const std::string& indenter = "",
                     const std::string& material = "") {
    writeBundle(dir / "slab", test::smallSlab(n, 0.25e-3, 1.0e-3));
    test::writeFile(scene, "bundle = \"slab\"\n[material]\nyoungs_modulus = 4.2e9\nfriction = 0.23\n" + material +
                           "[indenter]\nradius = 2.5e-3\nspeed = 0.03\n" + indenter + "[protocol]\ndelta_max = " +
                               std::to_string(deltaMax) + "\n[damping]\nlocal = 0.3\n[output]\ncheckpoint_seconds = 1e5\n" +
                               (solver.empty() ? "" : "[solver]\n" + solver + "\n"));
  }
  RunRequest request(const std::string& output = "") const {
    RunRequest r;
    r.scene = scene;
    r.output = output;
    r.threads = 1;
    return r;
  }
};

void requireSameCurve(const std::vector<CurveSample>& a, const std::vector<CurveSample>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    INFO("sample " << i);
    REQUIRE(a[i].time == b[i].time);
    REQUIRE(a[i].delta == b[i].delta);
    REQUIRE(a[i].load == b[i].load);
    REQUIRE(a[i].externalWork == b[i].externalWork);
    REQUIRE(a[i].residual == b[i].residual);
  }
}

}  // namespace

TEST_CASE("checkpoint round trip: a run stopped mid-loading and resumed in process ends bit-identical, either method, either stiffness rule") {
  const std::string method = GENERATE(std::string("explicit"), std::string("implicit"));
  const std::string rule = GENERATE(std::string("span"), std::string("bars"), std::string("sections"));  // bars, sections: found again from the start poses
  INFO("method " << method << ", stiffness rule " << rule);
  SmallTest t(3, 0.6e-3, "method = \"" + method + "\"", "", "stiffness_rule = \"" + rule + "\"\n");
  auto whole = RunSession::start(t.request(), {});
  whole->run({});
  REQUIRE(whole->record().stopReason == StopReason::DeltaMax);
  const long steps = whole->record().steps;

  auto first = RunSession::start(t.request(t.dir / "run"), {});
  RunHooks stopHalfway;
  stopHalfway.interrupted = [&] { return first->world().stepCount() >= steps / 2; };
  first->run(stopHalfway);
  REQUIRE(first->record().stopReason == StopReason::Interrupted);
  REQUIRE(first->state().phase == 1);  // stopped while loading
  REQUIRE_FALSE(first->record().curve.empty());
  first.reset();  // releases the folder

  auto resumed = RunSession::resume(t.dir / "run", "", "", -1, {});
  REQUIRE(resumed->world().stepCount() == steps / 2);
  resumed->run({});
  REQUIRE(resumed->record().stopReason == StopReason::DeltaMax);
  REQUIRE(resumed->world().stepCount() == steps);
  requireSameCurve(resumed->record().curve, whole->record().curve);
  const RigidBodies &a = resumed->world().bodies(), &b = whole->world().bodies();
  for (std::size_t i = 0; i < a.size(); ++i) {
    REQUIRE(a.position[i] == b.position[i]);
    REQUIRE(a.orientation[i].coeffs() == b.orientation[i].coeffs());
    REQUIRE(a.angularMomentum[i] == b.angularMomentum[i]);
  }
}

TEST_CASE("a bit flipped anywhere in checkpoint.h5 is refused or resumes exactly as before (issue #39)") {
  // HDF5 checksums the metadata, Fletcher-32 every dataset; what is read is checked again.
  SmallTest t;
  auto first = RunSession::start(t.request(t.dir / "run"), {});
  RunHooks stop;
  stop.interrupted = [&] { return first->state().phase == 1 && first->record().curve.size() >= 5; };
  first->run(stop);
  first.reset();
  const std::string file = t.dir / "run/checkpoint.h5";
  const auto resumed = [&] {
    auto r = RunSession::resume(t.dir / "run", "", "", -1, {});
    const IndentationState& s = r->state();
    std::ostringstream all;
    all.precision(17);
    all << stateDigest(r->world()) << r->source().sceneText << r->source().preset << r->source().threads << s.phase << s.sphere
        << s.loadStart << s.contactTravel << s.peak << s.nextSample << s.nextSnapshot << s.quietFrom << s.travelBase
        << s.pathBase << s.speedSince << s.contactPath << r->record().thickness << r->record().deltaMax
        << r->record().target << r->record().timeStep << r->world().state().externalWork << r->world().state().friction;
    for (const CurveSample& c : r->record().curve)
      for (const CurveColumn& column : curveColumns()) all << ' ' << c.*column.field;
    for (const PairState& p : r->world().state().pairs)
      for (const NodeContact& c : p.contacts)
        all << ' ' << c.key << ' ' << c.spring.x() << ' ' << c.spring.y() << ' ' << c.spring.z() << ' ' << c.energy << ' ' << c.area;
    return all.str();
  };
  const std::string original = resumed();
  test::BitFlips flips(test::readFile(file), 777);
  int refused = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const test::BitFlip flip = flips.next();
    test::writeFile(file, flip.bytes);
    INFO("a bit of byte " << flip.at << " of " << flip.bytes.size() << " flipped");
    std::string got;
    try {
      got = resumed();
    } catch (const InputError& e) {
      REQUIRE_THAT(e.what(), Contains("checkpoint.h5"));
      ++refused;
      continue;
    }
    REQUIRE(got == original);
  }
  REQUIRE(refused > 20);  // most of the file is free space and padding
}

TEST_CASE("a version-8 checkpoint (the indenter's work under its former name) resumes as written") {
  SmallTest t;
  auto first = RunSession::start(t.request(t.dir / "run"), {});
  RunHooks stop;
  stop.interrupted = [&] { return first->state().phase == 1 && first->record().curve.size() >= 5; };
  first->run(stop);
  const double work = first->world().state().externalWork;
  REQUIRE(work > 0);
  first.reset();
  {
    h5::Handle f(H5Fopen((t.dir / "run/checkpoint.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
    REQUIRE(f.get() >= 0);
    H5Adelete(f.get(), "format_version");
    h5::writeAttribute(f.get(), "format_version", std::int64_t{8});
    h5::Handle w = h5::openGroup(f.get(), "world");
    REQUIRE(H5Arename(w.get(), "external_work", "obstacle_work") >= 0);
  }
  REQUIRE(RunSession::resume(t.dir / "run", "", "", -1, {})->world().state().externalWork == work);
}

TEST_CASE("sample hook: a run it does not steer is the protocol's run, a hold does no work and keeps delta") {
  SmallTest t;
  auto plain = RunSession::start(t.request(), {});
  plain->run({});

  auto held = RunSession::start(t.request(), {});
  const double hold = 0.2e-3;
  double speed = 0;
  int heldSamples = 0;
  std::vector<std::size_t> during;
  RunHooks hooks;
  hooks.sample = [&](const CurveSample& s, IndentationControl& c) {
    if (speed == 0) speed = c.indenterSpeed;
    if (c.indenterSpeed != 0 && heldSamples == 0 && s.delta >= hold) c.indenterSpeed = 0;  // hold
    else if (c.indenterSpeed == 0) {
      during.push_back(held->record().curve.size() - 1);
      if (++heldSamples == 10) c.indenterSpeed = speed;  // and go on
    }
  };
  held->run(hooks);
  REQUIRE(held->record().stopReason == StopReason::DeltaMax);
  REQUIRE(during.size() == 10);
  const auto& curve = held->record().curve;
  const CurveSample& start = curve[during.front() - 1];  // the sample at which the hold began
  for (std::size_t i : during) {
    INFO("held sample " << i);
    REQUIRE(curve[i].delta == start.delta);                 // the indenter still
    REQUIRE(curve[i].externalWork == start.externalWork);  // and doing no work
    REQUIRE(curve[i].load <= start.load * 1.001);           // the slab relaxes under it
  }
  REQUIRE(curve[during.back()].time - start.time > 0);
  // Up to the hold the run is the protocol's, to the last bit.
  const std::size_t before = during.front();
  requireSameCurve(std::vector<CurveSample>(curve.begin(), curve.begin() + before),
                   std::vector<CurveSample>(plain->record().curve.begin(), plain->record().curve.begin() + before));
}

TEST_CASE("sample hook: stop() ends the run as requested, a finished run") {
  SmallTest t;
  auto session = RunSession::start(t.request(), {});
  RunHooks hooks;
  hooks.sample = [](const CurveSample& s, IndentationControl& c) { c.stop = s.delta >= 0.1e-3; };
  session->run(hooks);
  REQUIRE(session->record().stopReason == StopReason::Requested);
  REQUIRE(session->record().curve.back().delta >= 0.1e-3);
  REQUIRE(session->record().curve.back().delta < 0.1e-3 + 2 * 10e-6);
  REQUIRE(session->state().phase == 2);
  REQUIRE(session->response().failureMode == "none up to the requested stop");
}

TEST_CASE("presets and overrides reach the scene, and the span is resolved once") {
  SmallTest t;
  for (const Preset& preset : presets()) {
    INFO("preset " << preset.name);
    RunRequest r = t.request();
    r.preset = preset.name;
    const std::string text = "# x\n" + sceneWithOverrides(t.scene, preset.overrides);
    const Scene scene = readSceneText(text, t.scene);
    const Scene base = readScene(t.scene);
    REQUIRE(scene.contact.friction == base.contact.friction);  // presets set accuracy, not the material
    REQUIRE(RunSession::start(r, {})->source().preset == preset.name);
    // Every key the preset sets is the value its Scene field reads (a key read into the wrong
    // field, or not at all, would leave the field at the base scene's value).
    const std::map<std::string, double> fields{
        {"resolution.node_spacing", scene.resolution.nodeSpacing},
        {"resolution.node_spacing_ratio", scene.resolution.nodeSpacingRatio},
        {"resolution.edge_spacing_fraction", scene.resolution.edgeSpacingFraction},
        {"resolution.size_gradient", scene.resolution.sizeGradient},
        {"indenter.speed", scene.indenter.speed},
        {"indenter.speed_ratio", scene.indenter.speedRatio},
        {"solver.time_step_factor", scene.solver.timeStepFactor}};
    for (const auto& [key, value] : preset.overrides) {
      INFO("key " << key);
      REQUIRE(fields.count(key) == 1);
      REQUIRE(fields.at(key) == Approx(value).epsilon(1e-12));
    }
  }
  RunRequest r = t.request();
  r.overrides = {{"material.friction", 0.5}, {"indenter.speed", 0.01}};
  auto session = RunSession::start(r, {});
  REQUIRE(session->scene().contact.friction == 0.5);
  REQUIRE(session->scene().indenter.speed == 0.01);
  // The span: the bundle's (3 x 3 grid: L = 1 pitch, M = 2), unless the scene sets one.
  REQUIRE(session->contact().spanLength == Approx(10e-3));
  REQUIRE(session->contact().spanInterfaces == 2);
  r.overrides = {{"span.length", 0.02}, {"span.interfaces", 4}};
  REQUIRE(RunSession::start(r, {})->contact().spanLength == 0.02);
  r.overrides = {{"material.nonsense", 1}};
  REQUIRE_THROWS_AS(RunSession::start(r, {}), InputError);
  Bundle noSpan = test::smallSlab(3, 0.25e-3, 1.0e-3);
  noSpan.spanLength = 0;
  noSpan.spanInterfaces = 0;
  ContactParameters unset;
  unset.spanLength = 0;
  unset.spanInterfaces = 0;
  REQUIRE_THROWS_WITH(resolveSpan(unset, noSpan, "s.toml"), Contains("s.toml") && Contains("[span]"));
}

TEST_CASE("a run folder holds one run: a second start is refused while the first holds it, and after") {
  SmallTest t;
  auto first = RunSession::start(t.request(t.dir / "run"), {});
  REQUIRE_THROWS_WITH(RunSession::start(t.request(t.dir / "run"), {}), Contains("this process still holds a run there"));
  first->run({});
  first.reset();
  REQUIRE_THROWS_WITH(RunSession::start(t.request(t.dir / "run"), {}), Contains("holds a run already"));
}

TEST_CASE("determinism: the 7 x 7 slab ends in the same state, digest in summary.json, with 1, 2 and 4 threads") {
  test::TempDir dir;
  writeBundle(dir / "slab", test::smallSlab(7, 0.25e-3, 0.6e-3));
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nradius = 2.5e-3\nspeed = 0.03\n"
                                      "[protocol]\ndelta_max = 0.15e-3\n[damping]\nlocal = 0.3\n");
  std::vector<std::string> digests;
  std::vector<CurveSample> first;
  for (int threads : {1, 2, 4}) {
    RunRequest r;
    r.scene = dir / "scene.toml";
    r.threads = threads;
    r.output = dir / ("run" + std::to_string(threads));
    auto session = RunSession::start(r, {});
    session->run({});
    REQUIRE(session->record().stopReason == StopReason::DeltaMax);
    std::ifstream in(r.output + "/summary.json");
    const nlohmann::json summary = nlohmann::json::parse(in);
    REQUIRE(summary["state_digest"] == stateDigest(session->world()));
    digests.push_back(summary["state_digest"]);
    if (first.empty()) first = session->record().curve;
    else requireSameCurve(session->record().curve, first);
  }
  REQUIRE(digests[0].size() == 16);
  REQUIRE(digests[1] == digests[0]);
  REQUIRE(digests[2] == digests[0]);
}

TEST_CASE("implicit against explicit on a 5 x 5 slab past its peak: P_max and K within 1 %, W within 3 %, energy residual under 1 % to the peak, 3 % through the drop") {
  SmallTest explicitRun(5, 2.5e-3), implicitRun(5, 2.5e-3, "method = \"implicit\"");
  auto a = RunSession::start(explicitRun.request(), {});
  a->run({});
  auto b = RunSession::start(implicitRun.request(), {});
  b->run({});
  REQUIRE(b->record().implicit);
  REQUIRE(b->record().implicitCounts.iterations > 0);
  const ResponseParameters ra = a->response();
  const ResponseParameters rb = b->response();
  INFO("P_max " << ra.peakLoad << " / " << rb.peakLoad << ", K " << ra.stiffness << " / " << rb.stiffness << ", W "
                << ra.energyToEnd << " / " << rb.energyToEnd);
  REQUIRE(rb.peakLoad == Approx(ra.peakLoad).epsilon(0.01));
  REQUIRE(rb.stiffness == Approx(ra.stiffness).epsilon(0.01));
  REQUIRE(rb.energyToEnd == Approx(ra.energyToEnd).epsilon(0.03));
  REQUIRE(rb.deltaAtPeak == Approx(ra.deltaAtPeak).margin(0.1 * ra.thickness));
  // The residual is first-order in the increments where a node's nearest face switches or the
  // load drops within one (docs/physics.md, "Implicit method").
  for (const CurveSample& c : b->record().curve)
    if (c.delta <= rb.deltaAtPeak) REQUIRE(std::abs(c.residual) < 0.01 * c.externalWork + 1e-6);
  const CurveSample& end = b->record().curve.back();
  REQUIRE(std::abs(end.residual) < 0.03 * end.externalWork);
  REQUIRE(b->world().stepCount() < a->world().stepCount() / 50);
}

TEST_CASE("mirrored loads on a 5 x 5 slab give the same answer: P_max, K and W within 0.1 %, the same failure (issue #38)") {
  // The slab is symmetric under x -> -x and y -> -y (the block under both mirrors, the checkerboard
  // of turns too), and so are the blocks' nodes; a load at (12, 3) mm and its two mirror images
  // must then give the same response.
  std::vector<ResponseParameters> responses;
  for (const char* point : {"[0.012, 0.003]", "[-0.012, 0.003]", "[0.012, -0.003]"}) {
    SmallTest test(5, 2.5e-3, "", std::string("point = ") + point + "\n");
    auto run = RunSession::start(test.request(), {});
    run->run({});
    responses.push_back(run->response());
  }
  const ResponseParameters& a = responses[0];
  REQUIRE(a.peakLoad > 0);
  for (const ResponseParameters& b : responses) {
    INFO("P_max " << a.peakLoad << " / " << b.peakLoad << ", K " << a.stiffness << " / " << b.stiffness << ", W "
                  << a.energyToEnd << " / " << b.energyToEnd << ", failure " << a.failureMode << " / " << b.failureMode);
    REQUIRE(b.peakLoad == Approx(a.peakLoad).epsilon(1e-3));
    REQUIRE(b.stiffness == Approx(a.stiffness).epsilon(1e-3));
    REQUIRE(b.energyToEnd == Approx(a.energyToEnd).epsilon(1e-3));
    REQUIRE(b.failureMode == a.failureMode);
  }
}

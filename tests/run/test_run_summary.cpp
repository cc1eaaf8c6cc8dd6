// summary.json's one definition (RunSummary): what is written is what is read back, by the file's
// keys and units, and a summary with a key missing or of the wrong type is refused naming it.
#include "io/input_error.h"
#include "io/json_text.h"
#include "run/run_summary.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

// A summary with a distinct value in every field (a field the reader skipped, or read under
// another unit, would not come back equal).
RunSummary filled(bool failed) {
  RunSummary s;
  s.generator = "tessera test";
  s.scene = "scene.toml";
  s.bundle = "slab";
  s.target = "r3c3";
  s.stopReason = failed ? StopReason::Failure : StopReason::DeltaMax;
  s.stateDigest = "0123456789abcdef";
  ResponseParameters& r = s.response;
  r.peakLoad = 118.4;
  r.deltaAtPeak = 1.85e-3;
  r.peakRangeFrom = 1.67e-3;
  r.peakRangeTo = 2.22e-3;
  r.stiffness = 113.9e3;
  r.fitFrom = 0.0;
  r.fitTo = 0.4e-3;
  r.failureDeflection = failed ? 4.06e-3 : -1;
  r.energy = 0.3515;
  r.energyToEnd = 0.41;
  r.ultimateDeflection = 5.2e-3;
  r.failureMode = failed ? "loaded block out" : "no failure";
  r.drops = {{2.1e-3, 110.0, 80.5}, {3.3e-3, 60.0, 20.25}};
  r.atPeak = {1.85e-3, 1.2e-3, 0.3e-3, 0.25, 0.5, 0.03};
  r.atFailure = {4.06e-3, 3.9e-3, 0.1e-3, 0.75, 0.875, 0.029};
  r.end.delta = 5.5e-3;
  r.end.load = 1.5;
  r.end.blockDisplacement = 5.25e-3;
  r.end.externalWork = 0.41;
  r.end.elastic = 0.01;
  r.end.kinetic = 0.002;
  r.end.friction = 0.3;
  r.end.damping = 0.05;
  r.end.gravityWork = 0.004;
  r.end.retiredKinetic = 0.001;
  r.end.projection = 0.03;
  r.end.residual = 0.0002;
  r.quasiStaticRatio = 0.004;
  r.quasiStatic = true;
  r.loadingSpeed = 0.03;
  r.thickness = 3.18e-3;
  r.peakLoadNormalised = 0.0112;
  r.deltaAtPeakNormalised = 0.58;
  s.fallen = {{"r3c3", 4.1e-3, true, false}, {"r3c4", 4.2e-3, false, true}};
  s.failureLoadFraction = 0.1;
  s.quasiStaticTarget = 0.01;
  s.deltaMax = 6.36e-3;
  s.material = {4.2e9, 0.23, 5.04e11, 4.2e11, 2.0, 2.5e-3, 0.03, 50e-3, 6, "two-way", "blended", "sections"};
  s.shapes = {{"block", "planes", 0.25e-3, 0.6e-3, 0.15e-3, 704}};
  s.run = {"implicit", 1.25e-6, 167077, 900, 3, 7, 0.05, 4000, true, 1e-9, 1.68, 2, 19.5, 1200, 40};
  return s;
}

void requireEqual(const ContactState& a, const ContactState& b) {
  REQUIRE(a.delta == Approx(b.delta).epsilon(1e-15));
  REQUIRE(a.blockDisplacement == Approx(b.blockDisplacement).epsilon(1e-15));
  REQUIRE(a.indenterPenetration == Approx(b.indenterPenetration).epsilon(1e-15));
  REQUIRE(a.slidingFraction == b.slidingFraction);
  REQUIRE(a.loadedSlidingFraction == b.loadedSlidingFraction);
  REQUIRE(a.indenterSpeed == Approx(b.indenterSpeed).epsilon(1e-15));
}

}  // namespace

TEST_CASE("summary.json read back: every field as written, a failure's nulls as no failure") {
  for (bool failed : {true, false}) {
    INFO("failed: " << failed);
    const RunSummary written = filled(failed);
    const std::string text = jsonText(runSummaryJson(written));
    const RunSummary read = parseRunSummary(text);
    REQUIRE(jsonText(runSummaryJson(read)) == text);  // the same file again
    // Field by field, in SI units (each key's unit undone).
    REQUIRE(read.stopReason == written.stopReason);
    REQUIRE(read.target == "r3c3");
    REQUIRE(read.response.peakLoad == 118.4);
    REQUIRE(read.response.deltaAtPeak == Approx(1.85e-3).epsilon(1e-15));
    REQUIRE(read.response.peakRangeFrom == Approx(1.67e-3).epsilon(1e-15));
    REQUIRE(read.response.peakRangeTo == Approx(2.22e-3).epsilon(1e-15));
    REQUIRE(read.response.stiffness == Approx(113.9e3).epsilon(1e-15));
    REQUIRE(read.response.fitTo == Approx(0.4e-3).epsilon(1e-15));
    REQUIRE(read.response.energy == Approx(0.3515).epsilon(1e-15));
    REQUIRE(read.response.failureDeflection == (failed ? Approx(4.06e-3).epsilon(1e-15) : Approx(-1)));
    REQUIRE(read.response.drops.size() == 2);
    REQUIRE(read.response.drops[1].after == 20.25);
    requireEqual(read.response.atPeak, written.response.atPeak);
    if (failed) requireEqual(read.response.atFailure, written.response.atFailure);
    REQUIRE(read.response.end.residual == Approx(0.0002).epsilon(1e-15));
    REQUIRE(read.response.end.gravityWork == Approx(0.004).epsilon(1e-15));
    REQUIRE(read.fallen.size() == 2);
    REQUIRE(read.fallen[1].touching);
    REQUIRE(read.deltaMax == Approx(6.36e-3).epsilon(1e-15));
    REQUIRE(read.material.youngsModulus == Approx(4.2e9).epsilon(1e-15));
    REQUIRE(read.material.contactArea == "blended");
    REQUIRE(read.material.spanInterfaces == 6);
    REQUIRE(read.shapes.size() == 1);
    REQUIRE(read.shapes[0].nodes == 704);
    REQUIRE(read.shapes[0].edgeNodeSpacing == Approx(0.15e-3).epsilon(1e-15));
    REQUIRE(read.run.steps == 167077);
    REQUIRE(read.run.settled);
    REQUIRE(read.run.sunkWhileSettling == 2);
  }
}

TEST_CASE("summary.json keys: name and unit in the file, the plain name in SI units for Python") {
  const RunSummary s = filled(false);
  const nlohmann::json file = runSummaryJson(s), si = runSummaryJson(s, false);
  REQUIRE(file["response"]["delta_at_peak_mm"].get<double>() == Approx(1.85));
  REQUIRE(file["response"]["stiffness_N_per_mm"].get<double>() == Approx(113.9));
  REQUIRE(file["response"]["energy"]["external_work_mJ"].get<double>() == Approx(410));
  REQUIRE(file["material"]["youngs_modulus_GPa"].get<double>() == Approx(4.2));
  REQUIRE(file["response"]["failure_deflection_mm"].is_null());
  REQUIRE(file["response"]["at_failure"].is_null());
  REQUIRE(si["response"]["delta_at_peak"].get<double>() == 1.85e-3);
  REQUIRE(si["response"]["energy"]["external_work"].get<double>() == 0.41);
  REQUIRE(si["run"]["time_step"].get<double>() == 1.25e-6);
  REQUIRE(si["response"]["failure_deflection"].is_null());
}

TEST_CASE("summary.json: a value that is not finite is written as null and read back as NaN") {
  RunSummary s = filled(true);
  s.response.peakLoadNormalised = std::numeric_limits<double>::infinity();  // P* = P / (E L^2) without a span
  const std::string text = jsonText(runSummaryJson(s));
  REQUIRE(nlohmann::json::parse(text)["response"]["peak_load_normalised"].is_null());  // JSON has no infinity
  const RunSummary read = parseRunSummary(text);
  REQUIRE(std::isnan(read.response.peakLoadNormalised));
  REQUIRE(read.stopReason == StopReason::Failure);
}

TEST_CASE("a summary.json with a key missing, of the wrong type, or not JSON is refused naming the key, but for keys added later") {
  const nlohmann::json good = runSummaryJson(filled(true));
  nlohmann::json missing = good;
  missing["response"]["at_peak"].erase("indenter_speed_mm_per_s");
  REQUIRE_THROWS_WITH(parseRunSummary(missing.dump()), Contains("'response.at_peak.indenter_speed_mm_per_s'"));
  nlohmann::json wrong = good;
  wrong["run"]["steps"] = "many";
  REQUIRE_THROWS_WITH(parseRunSummary(wrong.dump()), Contains("'run.steps' is not a whole number"));
  nlohmann::json entry = good;
  entry["response"]["fallen"][1].erase("touching");
  REQUIRE_THROWS_WITH(parseRunSummary(entry.dump()), Contains("'response.fallen[1].touching'"));
  nlohmann::json reason = good;
  reason["stop_reason"] = "finished";
  REQUIRE_THROWS_WITH(parseRunSummary(reason.dump()), Contains("which no run writes"));
  // peak_range_mm came later: a summary without it reads back with the peak's delta alone.
  nlohmann::json older = good;
  older["response"].erase("peak_range_mm");
  const RunSummary read = parseRunSummary(older.dump());
  REQUIRE(read.response.peakRangeFrom == read.response.deltaAtPeak);
  REQUIRE(read.response.peakRangeTo == read.response.deltaAtPeak);
  REQUIRE_THROWS_AS(parseRunSummary("{\"stop_reason\": "), InputError);
  REQUIRE_THROWS_AS(parseRunSummary("[1, 2]"), InputError);
}

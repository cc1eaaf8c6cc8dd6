// Response analysis on synthetic curves whose K, P_max, failure deflection and W are known.
#include "run/response.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>

using namespace tessera;

namespace {

const double kStep = 0.04e-3;  // m between samples
const double kH = 3.18e-3;     // m, the block's thickness

// Samples delta = i kStep, i = 0..n, of P(delta); kinetic energy 1e-3 of the work so far.
IndentationRecord recordOf(int n, const std::function<double(double)>& load) {
  IndentationRecord r;
  r.thickness = kH;
  r.targetName = "centre";
  r.stopReason = StopReason::DeltaMax;
  double work = 0;
  for (int i = 0; i <= n; ++i) {
    CurveSample s;
    s.delta = i * kStep;
    s.load = load(s.delta);
    if (i > 0) work += 0.5 * (s.load + r.curve.back().load) * kStep;
    s.externalWork = work;
    s.kinetic = 1e-3 * work;
    r.curve.push_back(s);
  }
  return r;
}

// Up at K = 100 N/mm to 100 N at 1 mm, down linearly to 0 at 2 mm, then nothing.
double triangle(double delta) {
  const double mm = delta * 1e3;
  return mm <= 1 ? 100 * mm : mm <= 2 ? 100 * (2 - mm) : 0.0;
}

}  // namespace

TEST_CASE("response: K, P_max, failure deflection and W of a triangular curve") {
  const IndentationRecord record = recordOf(75, triangle);  // to 3 mm
  ResponseSettings settings;
  settings.youngsModulus = 4.2e9;
  settings.spanLength = 50e-3;
  settings.freeBodies = 25;
  const ResponseParameters r = analyseResponse(record, settings);
  REQUIRE(r.peakLoad == Approx(100.0).epsilon(1e-12));
  REQUIRE(r.deltaAtPeak == Approx(1e-3).epsilon(1e-12));
  // A sharp peak: only its own sample is within 1 % (96 N at 0.96 and 1.04 mm).
  REQUIRE(r.peakRangeFrom == r.deltaAtPeak);
  REQUIRE(r.peakRangeTo == r.deltaAtPeak);
  // The fit window ends at 0.4 mm (stiffnessFitRatio x h), before delta_peak / 2 = 0.5 mm.
  REQUIRE(r.fitTo == Approx(0.4e-3).epsilon(1e-9));
  REQUIRE(r.stiffness == Approx(100e3).epsilon(1e-9));
  // Failure: the first sample below 10 N after the peak is 1.92 mm (8 N; 1.88 mm has 12 N).
  REQUIRE(r.failureDeflection == Approx(1.92e-3).epsilon(1e-12));
  // W = 50 N mm + integral of 100 (2 - d) from 1 to 1.92 mm = 50 + 49.68 N mm (trapezoids exact on lines).
  REQUIRE(r.energy == Approx(99.68e-3).epsilon(1e-9));
  REQUIRE(r.energyToEnd == Approx(100e-3).epsilon(1e-9));
  REQUIRE(r.ultimateDeflection == Approx(2e-3).epsilon(1e-9));
  REQUIRE(r.quasiStaticRatio == Approx(1e-3).epsilon(1e-9));
  REQUIRE(r.quasiStatic);
  REQUIRE(r.failureMode == "none up to delta_max");
  REQUIRE(r.peakLoadNormalised == Approx(100.0 / (4.2e9 * 50e-3 * 50e-3)).epsilon(1e-12));
  REQUIRE(r.deltaAtPeakNormalised == Approx(1e-3 / kH).epsilon(1e-12));
}

TEST_CASE("response: a plateau and one sudden drop is one load drop, from where the fall starts") {
  const IndentationRecord record = recordOf(75, [](double delta) {
    const double mm = delta * 1e3;
    return mm <= 1 ? 100 * mm : mm < 2 - 1e-9 ? 100.0 : 50.0;
  });
  const ResponseParameters r = analyseResponse(record, ResponseSettings{});
  REQUIRE(r.drops.size() == 1);
  REQUIRE(r.drops[0].before == Approx(100.0));
  REQUIRE(r.drops[0].after == Approx(50.0));
  REQUIRE(r.drops[0].delta >= 1e-3);
  REQUIRE(r.drops[0].delta < 2e-3);
  REQUIRE(r.failureDeflection < 0);  // never below 10 N
  REQUIRE(r.energy == Approx(r.energyToEnd));
}

TEST_CASE("response: the failure mode follows the bodies out, and an unfinished run says so") {
  IndentationRecord record = recordOf(75, triangle);
  ResponseSettings settings;
  settings.freeBodies = 3;
  record.fallen = {{"centre", 2e-3, true, false}};
  REQUIRE(analyseResponse(record, settings).failureMode == "loaded block out");
  record.fallen.push_back({"r1c2", 2.1e-3, false, false});
  REQUIRE(analyseResponse(record, settings).failureMode == "2 blocks out");
  record.fallen.push_back({"r2c2", 2.2e-3, false, true});
  REQUIRE(analyseResponse(record, settings).failureMode == "collapse");
  record.fallen.clear();
  record.stopReason = StopReason::Interrupted;
  REQUIRE(analyseResponse(record, settings).failureMode == "none yet (run incomplete)");
  record.stopReason = StopReason::Requested;  // the sample hook ended it: a finished run
  REQUIRE(analyseResponse(record, settings).failureMode == "none up to the requested stop");
  record.stopReason = StopReason::Failure;  // the load lost with nothing out
  REQUIRE(analyseResponse(record, settings).failureMode == "load lost, no block out");
  record.stopReason = StopReason::DeltaMax;
  REQUIRE(analyseResponse(record, settings).failureMode == "none up to delta_max");
  REQUIRE(analyseResponse(IndentationRecord{}, settings).failureMode == "no contact");
}

TEST_CASE("response: a loading that goes too fast is flagged") {
  IndentationRecord record = recordOf(75, triangle);
  for (CurveSample& s : record.curve) s.kinetic = 0.05 * s.externalWork;
  const ResponseParameters r = analyseResponse(record, ResponseSettings{});
  REQUIRE(r.quasiStaticRatio == Approx(0.05));
  REQUIRE_FALSE(r.quasiStatic);
}

TEST_CASE("response: K is fitted on the first loading, not on an unloading and reloading after it") {
  // Up at 100 N/mm to 0.48 mm, back down at 400 N/mm to 0.25 mm, up again at 400 N/mm to 300 N (the
  // run's peak, past 0.8 mm), then a plateau.
  IndentationRecord record = recordOf(12, [](double delta) { return 100 * delta * 1e3; });  // to 0.48 mm
  const auto add = [&](double delta, double load) {
    CurveSample s;
    s.delta = delta;
    s.load = load;
    record.curve.push_back(s);
  };
  for (double mm = 0.5; mm > 0.25 - 1e-9; mm -= 0.04) add(mm * 1e-3, 50 - 400 * (0.5 - mm));
  for (double mm = 0.29; mm < 1.2 + 1e-9; mm += 0.04) add(mm * 1e-3, std::min(300.0, 50 + 400 * (mm - 0.25)));
  const ResponseParameters r = analyseResponse(record, ResponseSettings{});
  // The window ends at half the first loading's peak (50 N at 0.5 mm), not the reloading's: its own top.
  REQUIRE(r.fitTo == Approx(0.25e-3).epsilon(1e-9));
  REQUIRE(r.stiffness == Approx(100e3).epsilon(1e-9));  // the unloading and reloading (400 N/mm) left out
}

TEST_CASE("response: failure is read on the loading envelope, not where a steered run backs the indenter off") {
  // Up at 100 N/mm to 100 N at 1 mm, then the indenter backs off to 0.6 mm, unloading to 0 N.
  IndentationRecord record = recordOf(25, [](double delta) { return 100 * delta * 1e3; });
  const auto add = [&](double mm, double load) {
    CurveSample s;
    s.delta = mm * 1e-3;
    s.load = load;
    record.curve.push_back(s);
  };
  for (double mm = 0.96; mm > 0.6 - 1e-9; mm -= 0.04) add(mm, std::max(0.0, 100 - 300 * (1 - mm)));
  ResponseParameters r = analyseResponse(record, ResponseSettings{});
  REQUIRE(r.peakLoad == Approx(100.0));
  REQUIRE(r.failureDeflection < 0);  // none: the load fell to 0 N on the unloading
  REQUIRE(r.drops.empty());
  REQUIRE(r.ultimateDeflection == Approx(1e-3));  // the deepest point it carried load at
  REQUIRE(r.energy == Approx(r.energyToEnd));

  // Reloaded (below 1 mm it follows the unloading back up), then past 1 mm the load falls at
  // 220 N/mm: that is failure, at the first sample below 10 N on the envelope (1.40 mm: 12 N).
  for (double mm = 0.64; mm < 1.0 - 1e-9; mm += 0.04) add(mm, std::max(0.0, 100 - 300 * (1 - mm)));
  for (double mm = 1.0; mm < 1.6 + 1e-9; mm += 0.04) add(mm, std::max(0.0, 100 - 220 * (mm - 1)));
  r = analyseResponse(record, ResponseSettings{});
  REQUIRE(r.failureDeflection == Approx(1.44e-3).epsilon(1e-9));  // 3.2 N
  REQUIRE(r.drops.size() == 1);
  REQUIRE(r.drops[0].delta == Approx(1e-3));
}

TEST_CASE("response: the peak range spans the samples within 1 % of P_max, a second maximum nearly as high too") {
  // P = 100 (1 - 4 (d - 1)^2) N (d in mm) near the peak: within 1 % of P_max for |d - 1| <= (2 x 0.01
  // x 100 / 800)^1/2 = 0.05 mm, so the samples at 0.96, 1.00 and 1.04 mm.
  const auto parabola = [](double delta) { return std::max(0.0, 100 * (1 - 4 * (delta * 1e3 - 1) * (delta * 1e3 - 1))); };
  const ResponseParameters r = analyseResponse(recordOf(75, parabola), ResponseSettings{});
  REQUIRE(r.peakLoad == Approx(100.0).epsilon(1e-12));
  REQUIRE(r.deltaAtPeak == Approx(1e-3).epsilon(1e-12));
  REQUIRE(r.peakRangeFrom == Approx(0.96e-3).epsilon(1e-12));
  REQUIRE(r.peakRangeTo == Approx(1.04e-3).epsilon(1e-12));
  ResponseSettings wider;
  wider.peakRangeFraction = 0.1;  // |d - 1| <= 0.158 mm: 0.88 to 1.12 mm
  const ResponseParameters w = analyseResponse(recordOf(75, parabola), wider);
  REQUIRE(w.peakRangeFrom == Approx(0.88e-3).epsilon(1e-12));
  REQUIRE(w.peakRangeTo == Approx(1.12e-3).epsilon(1e-12));
  // A second hump, 99.5 N at 2 mm after a dip to 60 N, is within 1 % of P_max from 1.96 to 2.04 mm
  // ((d - 2)^2 <= 0.5 / 158): the highest sample could be there, and the range reaches it.
  const auto twoHumps = [&](double delta) {
    const double mm = delta * 1e3;
    return mm <= 1.5 ? parabola(delta) : 99.5 - 39.5 * std::min(1.0, 4 * (mm - 2) * (mm - 2));
  };
  const ResponseParameters h = analyseResponse(recordOf(75, twoHumps), ResponseSettings{});
  REQUIRE(h.deltaAtPeak == Approx(1e-3).epsilon(1e-12));
  REQUIRE(h.peakRangeFrom == Approx(0.96e-3).epsilon(1e-12));
  REQUIRE(h.peakRangeTo == Approx(2.04e-3).epsilon(1e-12));
  // No load at all: the range is the peak's sample (the first), not the whole run.
  const ResponseParameters none = analyseResponse(recordOf(75, [](double) { return 0.0; }), ResponseSettings{});
  REQUIRE(none.peakRangeFrom == none.deltaAtPeak);
  REQUIRE(none.peakRangeTo == none.deltaAtPeak);
}

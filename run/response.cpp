#include "run/response.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tessera {

namespace {

ContactState contactStateAt(const CurveSample& s) {
  return {s.delta, s.blockDisplacement, s.indenterPenetration, s.blockContacts > 0 ? s.slidingContacts / s.blockContacts : 0.0,
          s.loadedContacts > 0 ? s.loadedSliding / s.loadedContacts : 0.0, s.indenterSpeed};
}

// Trapezoidal area under P(delta) over samples [0, last].
double areaUpTo(const std::vector<CurveSample>& c, std::size_t last) {
  double w = 0;
  for (std::size_t i = 1; i <= last && i < c.size(); ++i) w += 0.5 * (c[i].load + c[i - 1].load) * (c[i].delta - c[i - 1].delta);
  return w;
}

// Sudden drops after sample `peak` (slip events): within a travel `window`, the load falls by at
// least `fraction` of its value where the fall starts, and by at least `floor` x `peakLoad` (so
// that the noise of a near-zero load is not one); one drop per such fall (the search restarts
// after it).
std::vector<LoadDrop> loadDrops(const std::vector<CurveSample>& c, std::size_t peak, double peakLoad, double fraction,
                                double floor, double window) {
  std::vector<LoadDrop> drops;
  std::size_t from = peak;
  for (std::size_t i = peak + 1; i < c.size(); ++i) {
    while (c[i].delta - c[from].delta > window) ++from;
    std::size_t top = from;
    for (std::size_t k = from; k <= i; ++k)
      if (c[k].load > c[top].load) top = k;
    if (c[top].load - c[i].load < std::max(fraction * c[top].load, floor * peakLoad)) continue;
    // Follow the fall to its bottom, then look for the next one from there.
    while (i + 1 < c.size() && c[i + 1].load < c[i].load) ++i;
    drops.push_back({c[top].delta, c[top].load, c[i].load});
    from = i;
  }
  return drops;
}

// K: least squares P = K delta + b over the fit window, on the first loading only (up to where
// delta first decreases: a steered run's unloading and reloading are not the initial stiffness).
void fitInitialStiffness(const std::vector<CurveSample>& c, double thickness, const ResponseSettings& settings,
                         ResponseParameters& r) {
  std::size_t firstLoading = 1;
  while (firstLoading < c.size() && c[firstLoading].delta >= c[firstLoading - 1].delta) ++firstLoading;
  std::size_t firstPeak = 0;  // the peak of the first loading (the run's peak when it only loads)
  for (std::size_t i = 1; i < firstLoading; ++i)
    if (c[i].load > c[firstPeak].load) firstPeak = i;
  r.fitFrom = 0.0;
  r.fitTo = std::min(settings.stiffnessFitRatio * thickness, 0.5 * c[firstPeak].delta);
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < firstLoading; ++i)
    if (const CurveSample& s = c[i]; s.delta >= r.fitFrom && s.delta <= r.fitTo) {
      n += 1;
      sx += s.delta;
      sy += s.load;
      sxx += s.delta * s.delta;
      sxy += s.delta * s.load;
    }
  if (n >= 2 && n * sxx - sx * sx > 0) r.stiffness = (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The loading envelope, where failure is read: the samples where the indenter is as deep as it
// has ever been. Below that (a steered run backing the indenter off, and reloading up to where
// it was) the load falls or rises because the indenter moves, not because the slab gives way.
std::vector<std::size_t> loadingEnvelope(const std::vector<CurveSample>& c) {
  std::vector<std::size_t> envelope;
  double deepest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i].delta >= deepest) {
      deepest = c[i].delta;
      envelope.push_back(i);
    }
  return envelope;
}

// The failure mode, from the final state.
std::string failureModeOf(const IndentationRecord& record, const ResponseSettings& settings) {
  const int fallen = static_cast<int>(record.fallen.size());
  const bool loadedOut = std::any_of(record.fallen.begin(), record.fallen.end(),
                                     [&](const FallenBody& f) { return f.name == record.targetName; });
  // With nothing out, the mode says how far the run looked: "no failure" alone read as a verdict
  // on a run a user had stopped at a delta_max of their choosing.
  if (fallen == 0) {
    if (record.stopReason == StopReason::DeltaMax) return "none up to delta_max";
    if (record.stopReason == StopReason::Failure) return "load lost, no block out";
    if (record.stopReason == StopReason::Requested) return "none up to the requested stop";
    return "none yet (run incomplete)";
  }
  if (settings.freeBodies > 1 && fallen >= settings.freeBodies) return "collapse";
  if (fallen == 1 && loadedOut) return "loaded block out";
  return std::to_string(fallen) + (fallen == 1 ? " block out" : " blocks out");
}

}  // namespace

ResponseParameters analyseResponse(const IndentationRecord& record, const ResponseSettings& settings) {
  ResponseParameters r;
  const auto& c = record.curve;
  r.thickness = record.thickness;
  if (c.empty()) {
    r.failureMode = "no contact";
    return r;
  }
  // Peak.
  std::size_t peak = 0;
  for (std::size_t i = 1; i < c.size(); ++i)
    if (c[i].load > c[peak].load) peak = i;
  r.peakLoad = c[peak].load;
  r.deltaAtPeak = c[peak].delta;
  r.atPeak = contactStateAt(c[peak]);
  // The peak range: where the highest sample could be were the loads 1 % (peakRangeFraction)
  // otherwise. Near a smooth peak it is |delta - delta(P_max)| <= (2 fraction P_max / -P'')^1/2; on a
  // flat peak it is the plateau, and a second maximum nearly as high extends it. (No load: the
  // peak's sample alone.)
  const double nearPeak = (1 - settings.peakRangeFraction) * r.peakLoad;
  r.peakRangeFrom = r.peakRangeTo = r.deltaAtPeak;
  if (r.peakLoad > 0)
    for (const CurveSample& s : c)
      if (s.load >= nearPeak) {
        r.peakRangeFrom = std::min(r.peakRangeFrom, s.delta);
        r.peakRangeTo = std::max(r.peakRangeTo, s.delta);
      }

  fitInitialStiffness(c, record.thickness, settings, r);

  const std::vector<std::size_t> envelope = loadingEnvelope(c);
  // From the peak on: the envelope's samples after it (the peak itself when it is one of them).
  const std::size_t peakOnEnvelope = static_cast<std::size_t>(
      std::lower_bound(envelope.begin(), envelope.end(), peak) - envelope.begin());
  const std::size_t afterPeak = peakOnEnvelope + (peakOnEnvelope < envelope.size() && envelope[peakOnEnvelope] == peak ? 1 : 0);

  // Failure deflection: the load first below the fraction of P_max after the peak.
  std::size_t failure = c.size() - 1;
  for (std::size_t k = afterPeak; k < envelope.size(); ++k)
    if (const std::size_t i = envelope[k]; c[i].load < settings.failureLoadFraction * r.peakLoad) {
      failure = i;
      r.failureDeflection = c[i].delta;
      break;
    }
  r.atFailure = contactStateAt(c[failure]);

  // Ultimate deflection: after the peak, where the load falls below 1 % of the peak for good.
  std::size_t last = envelope.back();
  for (std::size_t k = envelope.size(); k-- > std::min(peakOnEnvelope, envelope.size() - 1);)
    if (c[envelope[k]].load > 0.01 * r.peakLoad) {
      last = envelope[std::min(k + 1, envelope.size() - 1)];
      break;
    }
  r.ultimateDeflection = c[last].delta;

  r.energy = areaUpTo(c, failure);
  r.energyToEnd = areaUpTo(c, c.size() - 1);
  std::vector<CurveSample> loading;
  for (std::size_t i : envelope) loading.push_back(c[i]);
  r.drops = loadDrops(loading, std::min(peakOnEnvelope, loading.size() - 1), r.peakLoad, 0.1, 0.02, 0.05 * record.thickness);
  r.end = c.back();

  // Quasi-static check before the peak, once the indenter has done 1 % of its work up to the peak
  // (before that the ratio only measures the settling's leftover motion against almost nothing).
  for (std::size_t i = 0; i <= peak; ++i)
    if (c[i].externalWork > 0.01 * c[peak].externalWork)
      r.quasiStaticRatio = std::max(r.quasiStaticRatio, c[i].kinetic / c[i].externalWork);
  r.quasiStatic = r.quasiStaticRatio <= settings.quasiStaticLimit;
  if (c[peak].time > c[0].time) r.loadingSpeed = (c[peak].delta - c[0].delta) / (c[peak].time - c[0].time);

  r.failureMode = failureModeOf(record, settings);

  if (settings.youngsModulus > 0 && settings.spanLength > 0)
    r.peakLoadNormalised = r.peakLoad / (settings.youngsModulus * settings.spanLength * settings.spanLength);
  if (r.thickness > 0) r.deltaAtPeakNormalised = r.deltaAtPeak / r.thickness;
  return r;
}

}  // namespace tessera

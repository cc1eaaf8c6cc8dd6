#include "solver/response.h"

#include <algorithm>
#include <cmath>

namespace tessera {

ResponseParameters analyseResponse(const IndentationRecord& record, double youngsModulus, double spanLength,
                                   double thickness) {
  ResponseParameters r;
  const auto& c = record.curve;
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

  // K: least squares P = K delta + b over the fit window.
  r.fitFrom = 0.0;
  r.fitTo = std::min(0.4e-3, 0.5 * r.deltaAtPeak);
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const CurveSample& s : c)
    if (s.delta >= r.fitFrom && s.delta <= r.fitTo) {
      n += 1;
      sx += s.delta;
      sy += s.load;
      sxx += s.delta * s.delta;
      sxy += s.delta * s.load;
    }
  if (n >= 2 && n * sxx - sx * sx > 0) r.stiffness = (n * sxy - sx * sy) / (n * sxx - sx * sx);

  // Ultimate deflection: after the peak, where the load falls below 1 % of the peak for good.
  std::size_t last = c.size() - 1;
  for (std::size_t i = c.size(); i-- > peak;)
    if (c[i].load > 0.01 * r.peakLoad) {
      last = std::min(i + 1, c.size() - 1);
      break;
    }
  r.ultimateDeflection = c[last].delta;

  // W: trapezoidal area under P(delta) up to the ultimate deflection.
  for (std::size_t i = 1; i <= last; ++i) r.energy += 0.5 * (c[i].load + c[i - 1].load) * (c[i].delta - c[i - 1].delta);

  // Quasi-static check before the peak, once the indenter has done 1 % of its work up to the peak
  // (before that the ratio only measures the settling's leftover motion against almost nothing).
  for (std::size_t i = 0; i <= peak; ++i)
    if (c[i].externalWork > 0.01 * c[peak].externalWork)
      r.quasiStaticRatio = std::max(r.quasiStaticRatio, c[i].kinetic / c[i].externalWork);

  const bool targetFell = std::any_of(record.fallen.begin(), record.fallen.end(),
                                      [&](const FallenBody& f) { return f.name == record.targetName; });
  if (record.fallen.size() > 1) r.failureMode = "collapse";
  else if (targetFell) r.failureMode = "central block out";
  else r.failureMode = "no failure by delta_max";

  if (youngsModulus > 0 && spanLength > 0) r.peakLoadNormalised = r.peakLoad / (youngsModulus * spanLength * spanLength);
  r.thickness = thickness;
  if (thickness > 0) r.deltaAtPeakNormalised = r.deltaAtPeak / thickness;
  return r;
}

}  // namespace tessera

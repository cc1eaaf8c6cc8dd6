#pragma once
#include "run/indentation.h"

#include <string>
#include <vector>

namespace tessera {

/// What the analysis needs besides the record.
struct ResponseSettings {
  double youngsModulus = 0;        ///< Pa, for P* = P / (E L^2)
  double spanLength = 0;           ///< m
  double failureLoadFraction = 0.1;  ///< failure: the load first below this x P_max after the peak
  int freeBodies = 0;              ///< free bodies of the slab ("collapse": all of them fell)
  double stiffnessFitRatio = 0.4e-3 / kPaperThickness;  ///< K's fit window ends at this x h (or at delta_peak / 2)
  double quasiStaticLimit = 1e-2;  ///< quasiStatic is false above this KE / W before the peak
  double peakRangeFraction = 0.01;  ///< the peak range: where P is within this fraction of P_max
};

/// A sudden fall of the load after the peak (a slip event): within 0.05 h of travel, by at least
/// 10 % of the load where it starts and at least 2 % of P_max.
struct LoadDrop {
  double delta = 0;             ///< m, where the load began to fall
  double before = 0, after = 0; ///< N
};

/// The stick/slip state at one sample.
struct ContactState {
  double delta = 0;                ///< m
  double blockDisplacement = 0;    ///< m, delta_b of the loaded block
  double indenterPenetration = 0;  ///< m
  double slidingFraction = 0;      ///< of the node contacts between bodies, the fraction at the Coulomb cap
  double loadedSlidingFraction = 0;  ///< the same on the loaded block's interfaces
  double indenterSpeed = 0;        ///< m/s, the indenter's downward speed
};

/// The response parameters of an indentation (docs/outputs.md; Feldfogel et al., Fig. 1d).
struct ResponseParameters {
  double peakLoad = 0;            ///< N, P_max
  double deltaAtPeak = 0;         ///< m
  /// m, the peak range: the least and the greatest delta of the samples where P is within
  /// ResponseSettings::peakRangeFraction of P_max, where delta at P_max could be were the loads that
  /// much otherwise (on a flat peak, anywhere on it).
  double peakRangeFrom = 0, peakRangeTo = 0;
  double stiffness = 0;           ///< N/m, K: least-squares slope of P(delta) over the fit window
  double fitFrom = 0, fitTo = 0;  ///< m, the fit window
  /// m, where the load first falls below failureLoadFraction x P_max after the peak; < 0: it never does.
  double failureDeflection = -1;
  double energy = 0;              ///< J, W: area under P(delta) up to the failure deflection (or the end)
  double energyToEnd = 0;         ///< J, area under P(delta) over the whole run
  double ultimateDeflection = 0;  ///< m: where the load returns below 1 % of P_max for good, else the last delta
  std::string failureMode;        ///< from the final state: "no failure", "none yet (run incomplete)", "loaded block out", "N blocks out", "collapse"
  std::vector<LoadDrop> drops;    ///< every sudden load drop after the peak, the main one first
  ContactState atPeak, atFailure; ///< atFailure: at the failure deflection (or the end)
  CurveSample end;                ///< the last sample: energies at the end of the run
  double quasiStaticRatio = 0;    ///< max kinetic energy / external work before the peak (once 1 % of that work is done)
  bool quasiStatic = true;        ///< quasiStaticRatio is within ResponseSettings::quasiStaticLimit
  double loadingSpeed = 0;        ///< m/s, the indenter's mean speed from first contact to the peak (delta / time)
  double thickness = 0;           ///< m, h of the loaded block
  /// Normalised (the paper's upper-bound comparison): P* = P / (E L^2), delta* = delta / h.
  double peakLoadNormalised = 0, deltaAtPeakNormalised = 0;
};

/// Fit window for K: [0, min(stiffnessFitRatio x h, delta at the peak / 2)] (the paper's phase I
/// ends near 0.4 mm = 0.126 h on its block).
ResponseParameters analyseResponse(const IndentationRecord& record, const ResponseSettings& settings);

}  // namespace tessera

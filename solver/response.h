#pragma once
#include "solver/indentation.h"

#include <string>

namespace tessera {

/// The response parameters of an indentation (DESIGN §7; Feldfogel et al., Fig. 1d).
struct ResponseParameters {
  double peakLoad = 0;            ///< N, P_max
  double deltaAtPeak = 0;         ///< m
  double stiffness = 0;           ///< N/m, K: least-squares slope of P(delta) over the fit window
  double fitFrom = 0, fitTo = 0;  ///< m, the fit window
  double energy = 0;              ///< J, W: area under P(delta) up to the ultimate deflection
  double ultimateDeflection = 0;  ///< m: where the load returns to zero for good (below 1 % of P_max), else the last delta
  std::string failureMode;        ///< "central block out", "collapse", "no failure by delta_max"
  double quasiStaticRatio = 0;    ///< max kinetic energy / external work before the peak (once 1 % of that work is done)
  double thickness = 0;           ///< m, h of the loaded block
  /// Normalised (the paper's upper-bound comparison): P* = P / (E L^2), delta* = delta / h.
  double peakLoadNormalised = 0, deltaAtPeakNormalised = 0;
};

/// Fit window for K: [0, min(0.4 mm, delta at the peak / 2)] (the paper's phase I ends near 0.4 mm).
ResponseParameters analyseResponse(const IndentationRecord& record, double youngsModulus, double spanLength,
                                   double thickness);

}  // namespace tessera

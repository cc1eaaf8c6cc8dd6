#pragma once
#include "run/indentation.h"

#include <hdf5.h>

#include <vector>

namespace tessera {

/// One column of the load-deflection record: its name in results.h5 and checkpoints, its unit,
/// and the field of CurveSample it holds (docs/outputs.md).
struct CurveColumn {
  const char* name;
  const char* unit;
  double CurveSample::*field;
};

/// Every column, in the order they are written.
const std::vector<CurveColumn>& curveColumns();

/// The curve as one dataset per column (attribute `unit`) in `group`: the one layout of results.h5
/// and checkpoint.h5.
void writeCurve(hid_t group, const std::vector<CurveSample>& curve);
/// Reads what writeCurve wrote; throws std::runtime_error when a column is missing or its length differs.
std::vector<CurveSample> readCurve(hid_t group);

}  // namespace tessera

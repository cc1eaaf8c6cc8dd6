#include "run/curve_table.h"

#include "io/hdf5_file.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera {

const std::vector<CurveColumn>& curveColumns() {
  static const std::vector<CurveColumn> columns{
      {"time", "s", &CurveSample::time},
      {"delta", "m", &CurveSample::delta},
      {"load", "N", &CurveSample::load},
      {"block_displacement", "m", &CurveSample::blockDisplacement},
      {"indenter_penetration", "m", &CurveSample::indenterPenetration},
      {"contacts", "count", &CurveSample::contacts},
      {"block_contacts", "count", &CurveSample::blockContacts},
      {"sliding_contacts", "count", &CurveSample::slidingContacts},
      {"loaded_contacts", "count", &CurveSample::loadedContacts},
      {"loaded_sliding", "count", &CurveSample::loadedSliding},
      {"kinetic_energy", "J", &CurveSample::kinetic},
      {"external_work", "J", &CurveSample::externalWork},
      {"elastic_energy", "J", &CurveSample::elastic},
      {"friction_dissipated", "J", &CurveSample::friction},
      {"damping_dissipated", "J", &CurveSample::damping},
      {"gravity_work", "J", &CurveSample::gravityWork},
      {"retired_kinetic", "J", &CurveSample::retiredKinetic},
      {"projection_energy", "J", &CurveSample::projection},
      {"energy_residual", "J", &CurveSample::residual},
      {"indenter_speed", "m/s", &CurveSample::indenterSpeed},
  };
  return columns;
}

void writeCurve(hid_t group, const std::vector<CurveSample>& curve) {
  for (const CurveColumn& c : curveColumns()) {
    std::vector<double> values;
    values.reserve(curve.size());
    for (const CurveSample& s : curve) values.push_back(s.*c.field);
    h5::writeDataset(group, c.name, values, {curve.size()});
    h5::writeDatasetAttribute(group, c.name, "unit", c.unit);
  }
}

std::vector<CurveSample> readCurve(hid_t group) {
  std::vector<CurveSample> curve;
  bool first = true;
  for (const CurveColumn& c : curveColumns()) {
    const std::vector<double> values = h5::readDataset<double>(group, c.name);
    if (first) curve.resize(values.size());
    first = false;
    if (values.size() != curve.size())
      throw std::runtime_error(std::string("curve column '") + c.name + "' has " + std::to_string(values.size()) +
                               " values, not " + std::to_string(curve.size()));
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!std::isfinite(values[i]))
        throw std::runtime_error(std::string("curve column '") + c.name + "' holds a value that is not finite");
      curve[i].*c.field = values[i];
    }
  }
  return curve;
}

}  // namespace tessera

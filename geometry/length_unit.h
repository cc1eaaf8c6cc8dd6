#pragma once
#include <string>

namespace tessera {

/// A length unit of a mesh file. Mesh files carry no units, so every import states one.
struct LengthUnit {
  std::string name;  ///< as given: "mm", "cm", "m", "um", "in", "ft"
  double metres;     ///< metres per unit (mm -> 1e-3)
};

/// Parses a unit name; throws InputError listing the accepted names otherwise.
LengthUnit parseLengthUnit(const std::string& name);

/// A length for messages: metres shown in mm to 4 significant digits ("3.18 mm").
std::string formatMillimetres(double metres);

}  // namespace tessera

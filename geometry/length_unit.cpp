#include "geometry/length_unit.h"

#include "io/input_error.h"

#include <array>
#include <cstdio>
#include <utility>

namespace tessera {

LengthUnit parseLengthUnit(const std::string& name) {
  static const std::array<std::pair<const char*, double>, 6> known{{
      {"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"um", 1e-6}, {"in", 0.0254}, {"ft", 0.3048}}};
  for (const auto& [unit, metres] : known)
    if (name == unit) return {name, metres};
  throw InputError("unknown length unit '" + name + "': use one of m, cm, mm, um, in, ft");
}

std::string formatMillimetres(double metres) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g mm", metres * 1e3);
  return buffer;
}

}  // namespace tessera

#include "run/loading_rate.h"

#include <algorithm>
#include <cmath>

namespace tessera {

double adaptedIndenterSpeed(double speed, double ratio, double recent, double target, double slowest, double fastest) {
  if (ratio > target) {
    const double cut = std::max(0.8 * std::sqrt(target / ratio), 0.25);
    return std::max(speed * cut, std::min(slowest, speed));
  }
  if (recent < 0.25 * target) return std::min(speed * 1.25, fastest);
  return speed;
}

}  // namespace tessera

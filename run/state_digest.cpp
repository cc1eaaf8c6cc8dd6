#include "run/state_digest.h"

#include "io/file_digest.h"

namespace tessera {

std::string stateDigest(const World& world) {
  const RigidBodies& b = world.bodies();
  std::string bytes;
  const auto add = [&](const double* values, std::size_t count) {
    bytes.append(reinterpret_cast<const char*>(values), count * sizeof(double));
  };
  for (std::size_t i = 0; i < b.size(); ++i) {
    add(b.position[i].data(), 3);
    add(b.orientation[i].coeffs().data(), 4);
    add(b.velocity[i].data(), 3);
    add(b.angularMomentum[i].data(), 3);
  }
  const double clock[2] = {world.time(), static_cast<double>(world.stepCount())};
  add(clock, 2);
  return textDigest(bytes);
}

}  // namespace tessera

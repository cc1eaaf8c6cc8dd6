// The protocol's defaults that follow the slab (docs/scene.md, "Scale").
#include "run/protocol_scale.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tessera {

namespace {

// |g|; without gravity, standard gravity sets the scale (the criteria stay those of the same slab).
double gravityScale(const World& world) {
  const double g = world.settings().gravity.norm();
  return g > 0 ? g : 9.80665;
}

}  // namespace

double settleThreshold(const World& world, const ProtocolSettings& protocol) {
  if (protocol.settleKinetic > 0) return protocol.settleKinetic;
  const RigidBodies& b = world.bodies();
  const double g = gravityScale(world);
  double scale = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.moves(i)) scale += b.mass[i] * g * world.bodySize(static_cast<int>(i));
  return protocol.settleKineticRatio * scale;
}

double settleTimeLimit(const World& world, const ProtocolSettings& protocol) {
  if (protocol.settleMaxTime > 0) return protocol.settleMaxTime;
  std::vector<double> sizes;
  for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i)
    if (world.bodies().moves(i)) sizes.push_back(world.bodySize(i));
  if (sizes.empty()) return 0.0;
  std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
  const double t = sizes[sizes.size() / 2];
  const ContactParameters& p = world.parameters();
  const double c = std::sqrt(p.youngsModulus / world.settings().density);
  const double g = gravityScale(world);
  // The longer of a plate's period scale and twice the time to fall a block's size from rest.
  return std::max(protocol.settleMaxTimeRatio * p.spanLength * p.spanLength / (c * t), 2 * std::sqrt(2 * t / g));
}

double indenterSpeed(const World& world, const IndenterSettings& indenter, double thickness) {
  if (indenter.speed > 0) return indenter.speed;
  const ContactParameters& p = world.parameters();
  const double slenderness = thickness / p.spanLength;
  return indenter.speedRatio * std::sqrt(p.youngsModulus / world.settings().density) * slenderness * slenderness;
}

}  // namespace tessera

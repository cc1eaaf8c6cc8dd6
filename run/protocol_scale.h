#pragma once
// The protocol's defaults that follow the slab: each is the paper's value as a ratio of the size or
// time it scales with (docs/scene.md, "Scale"; tests/run/test_protocol_scale.cpp).
#include "run/scene.h"
#include "solver/world.h"

namespace tessera {

/// The settle threshold, J: protocol.settleKinetic, or settleKineticRatio x sum over free bodies of
/// m_i |g| h_i (h_i the body's size, World::bodySize; standard gravity when gravity is off): a
/// fraction of the energy of lifting every block by its own thickness, the same at any scale.
double settleThreshold(const World& world, const ProtocolSettings& protocol);

/// The longest settling, s: protocol.settleMaxTime, or the longer of settleMaxTimeRatio x L^2 / (c t)
/// (a plate's period scale: c = sqrt(E / rho), t the free bodies' median size, L the span) and
/// 2 sqrt(2 t / g), twice the time to fall t from rest (a block that is not held must get to sink).
double settleTimeLimit(const World& world, const ProtocolSettings& protocol);

/// The indenter's speed, m/s: indenter.speed, or speedRatio x c (h / L)^2 with c = sqrt(E / rho)
/// and L the span (scene.h, kPaperSpeedRatio): the same quasi-static ratio on any slab at any scale.
double indenterSpeed(const World& world, const IndenterSettings& indenter, double thickness);

}  // namespace tessera

#pragma once

namespace tessera {

/// Adaptive loading rate (docs/physics.md, "Adaptive loading rate"). At a sample where the quasi-static
/// ratio q = KE / W is measured, the next indenter speed (m/s) from the current one, v. The
/// kinetic energy of a slab following the indenter goes as v^2 at a given deflection, so
/// v sqrt(target / q) would give q = target: above the target the speed is cut to 0.8 of that
/// (at most 4x slower per sample), down to `slowest` (a speed already below it is kept). The slab
/// vibrates, and q with it, by orders of magnitude from sample to sample: the speed is raised, by
/// a quarter and up to `fastest` (the protocol's speed), only when the largest q of the recent
/// samples (`recent`, this one included) is below a quarter of the target. Otherwise it is kept.
double adaptedIndenterSpeed(double speed, double ratio, double recent, double target, double slowest, double fastest);

/// The samples `recent` covers.
inline constexpr int kRecentSamples = 8;

/// The slowest adaptive speed, as a fraction of the protocol's speed (the indenter starts at it):
/// a run never takes more than 1 / this times the steps of the protocol's speed.
inline constexpr double kSlowestSpeedFraction = 1.0 / 64;

}  // namespace tessera

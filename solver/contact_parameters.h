#pragma once

namespace tessera {

/// The contact law's parameters (docs/physics.md). Defaults: the paper's material and slab.
struct ContactParameters {
  double youngsModulus = 4.2e9;   ///< E, Pa
  double spanLength = 50e-3;      ///< L, m: free span of the slab
  int spanInterfaces = 6;         ///< M: interfaces across the span
  double tangentialRatio = 1.0;   ///< k_t / k_n
  /// > 0: k_t in N/m^3, fixed whatever E (instead of tangentialRatio x k_n).
  double tangentialStiffnessAbsolute = 0.0;
  double friction = 0.23;         ///< mu, Coulomb coefficient
  double normalViscosity = 0.0;   ///< eta_n, Pa s / m: normal damping traction per unit approach speed
  /// > 0: replace the traction law by a per-node stiffness (N/m, f = k_node d), which does not
  /// converge under node refinement. For demonstrating exactly that; never for results.
  double perNodeStiffness = 0.0;

  /// k_n = E M / L, N/m^3: normal traction per unit penetration (Feldfogel et al., Eq. 1).
  double normalStiffness() const { return youngsModulus * spanInterfaces / spanLength; }
  /// k_t, N/m^3: the absolute value when given, else (k_t/k_n) k_n.
  double tangentialStiffness() const {
    return tangentialStiffnessAbsolute > 0 ? tangentialStiffnessAbsolute : tangentialRatio * normalStiffness();
  }
};

}  // namespace tessera

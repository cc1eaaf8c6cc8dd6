#pragma once

namespace tessera {

/// Which nodes of a pair of bodies are tested, and with what share of their areas (docs/physics.md,
/// "Contact evaluation"): both bodies' nodes in the other's level set with half their areas
/// (two-way, Tessera's default: symmetric in a and b), or only the smaller body's nodes, with their
/// whole areas, in the larger body's level set (one-way: the master-slave rule of YADE's LS-DEM,
/// LAMMPS ls/dem and Kawamoto et al. 2016; equal volumes: a's nodes).
enum class ContactEvaluation { TwoWay, OneWay };

/// A node's effective area inside a convex body (exact planes; docs/physics.md, "Contact area"):
/// its area projected on the nearest face's plane, which jumps where the nearest face switches
/// at an edge with the node inside (nearest: the stored energy changes there without work), or
/// blended over the faces near the nearest one, continuous, with the force of its potential
/// (blended, solver/blended_area.h). Other level sets (meshes, grids, obstacles) take the nearest
/// surface point's normal either way.
enum class ContactArea { Blended, Nearest };

/// Which stiffness each contact gets (docs/physics.md, "Contact stiffness"): one k_n = E M / L for
/// every contact (span: the paper's rule, from the slab's free span), or k_n = E / (w_a + w_b) per
/// pair, w the length of the elastic bar from each body's centroid to the contact, 0 for a fixed
/// body or an obstacle (bars: from the blocks' own geometry, for any assembly), or the bars
/// weighted by each block's own sections (sections; ContactBars).
enum class StiffnessRule { Span, Bars, Sections };

/// The scene's name of a rule: "span", "bars", "sections".
inline const char* stiffnessRuleName(StiffnessRule rule) {
  return rule == StiffnessRule::Bars ? "bars" : rule == StiffnessRule::Sections ? "sections" : "span";
}

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
  ContactEvaluation evaluation = ContactEvaluation::TwoWay;  ///< scene: solver.contact_evaluation
  StiffnessRule stiffnessRule = StiffnessRule::Span;          ///< scene: material.stiffness_rule
  ContactArea area = ContactArea::Nearest;                    ///< scene: solver.contact_area

  /// The share of its area each node of side `side` of a body pair (a, b) carries (side 0: a's
  /// nodes in b; side 1: b's in a), given the bodies' volumes: 0.5 two-way; one-way 1 for the
  /// smaller body's side, 0 (not evaluated) for the other's.
  double sideAreaShare(int side, double volumeA, double volumeB) const {
    if (evaluation == ContactEvaluation::TwoWay) return 0.5;
    const int evaluated = volumeB < volumeA * (1 - 1e-9) ? 1 : 0;  // ties (the same shape): a's nodes
    return side == evaluated ? 1.0 : 0.0;
  }

  /// k_n = E M / L, N/m^3: normal traction per unit penetration (Feldfogel et al., Eq. 1).
  double normalStiffness() const { return youngsModulus * spanInterfaces / spanLength; }
  /// k_t, N/m^3: the absolute value when given, else (k_t/k_n) k_n.
  double tangentialStiffness() const {
    return tangentialStiffnessAbsolute > 0 ? tangentialStiffnessAbsolute : tangentialRatio * normalStiffness();
  }
};

}  // namespace tessera

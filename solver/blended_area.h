#pragma once
// The effective area of a node inside a convex body, blended over the body's planes near the
// nearest one, so that the stored energy 1/2 k_n a d^2 is a continuous function of where the node
// is and the contact force derives from it (docs/physics.md, "Contact area").
//
// Inside a convex body of planes k (depth below plane k: g_k = -(n_k . p - o_k); the node's depth
// d = min_k g_k = -phi), plane k takes part with the weight
//     rho_k = s(t_k),  t_k = (g_k - d) / (c d),  s(t) = (1 - t)^2 (1 + 2 t) for t < 1, else 0
// (the nearest plane t = 0, rho = 1; s is C1 and 0 from t = 1 on), and the node's area is
//     a = share sum_k rho_k P_k / sum_k rho_k,   P_k = A max(0, -n_i . n_k),
// its area projected on each plane near enough. Far from an edge (every other plane deeper than
// (1 + c) d) that is the nearest plane's projection: a face pressed on a face keeps the traction
// k_n d exactly. At an edge, where the nearest plane switches with the node inside, a changes
// continuously instead of jumping; the contact then also carries the potential's force along the
// area's gradient, -1/2 k_n d^2 grad a. t_k is homogeneous in the depths, so the blend is a wedge
// about the edge's bisector whose width grows with d: no length scale of its own.
//     grad t_k = (n_1 - n_k) / (c d) + t_k n_1 / d   (n_1 the nearest plane's normal, grad d = -n_1)
//     grad a = share sum_k s'(t_k) (P_k - a / share) grad t_k / sum_k rho_k,  s'(t) = -6 t (1 - t)
// The function returns d grad a, which stays bounded as d -> 0 where grad a alone does not.

namespace tessera {

/// c: a plane takes part in a node's area while its depth is below (1 + c) d. With c = 1 the
/// potential's force is at most about the normal force itself and its stiffness a few times a
/// node's normal stiffness (the explicit step's bound takes a whole face: docs/physics.md).
constexpr double kAreaBlendWidth = 1.0;

/// A node's blended area (m^2) and the depth times its gradient in the node's position, d grad a
/// (m^2; in the planes' frame).
template <class V>
struct BlendedArea {
  V area, slopeX, slopeY, slopeZ;
};

/// The blended area of nodes at p (x, y, z) inside a convex body given by `planes` (count, nx, ny,
/// nz, offset: n_k . p - o_k, in p's frame), with phi = max_k (n_k . p - o_k) < 0 and (n1x, n1y,
/// n1z) the first plane of largest value's normal; (ax, ay, az) each node's area times its outward
/// normal and `share` the share of it the node carries; into `out`. V: double, or a vector of
/// doubles (lanes whose phi is not negative give values to be ignored, not NaN traps; vectors by
/// reference, which keeps the ABI of every CPU version the same).
template <class V, class Planes>
__attribute__((always_inline)) inline void blendedArea(const Planes& planes, const V& x, const V& y, const V& z, const V& phi,
                                                       const V& n1x, const V& n1y, const V& n1z, const V& ax, const V& ay,
                                                       const V& az, double share, BlendedArea<V>& out) {
  constexpr double c = kAreaBlendWidth;
  const V zero{}, one = zero + 1.0;
  const V depth = -phi;
  const V perWidth = one / (c * (depth > 0 ? depth : one));  // 1 / (c d)
  V weights = zero, weighted = zero;
  for (int k = 0; k < planes.count; ++k) {
    const V gap = phi - (planes.nx[k] * x + planes.ny[k] * y + planes.nz[k] * z - planes.offset[k]);
    const V t = gap > 0 ? gap * perWidth : zero;  // 0 for the nearest plane; inf, not NaN, where 1 / (c d) overflows
    const V rho = t < 1.0 ? (one - t) * (one - t) * (one + 2.0 * t) : zero;
    const V p = -(ax * planes.nx[k] + ay * planes.ny[k] + az * planes.nz[k]);
    weights += rho;
    weighted += rho * (p > 0 ? p : zero);
  }
  const V mean = weighted / weights;  // the nearest plane has rho = 1: weights >= 1
  V gx = zero, gy = zero, gz = zero;
  for (int k = 0; k < planes.count; ++k) {
    const V gap = phi - (planes.nx[k] * x + planes.ny[k] * y + planes.nz[k] * z - planes.offset[k]);
    const V t = gap > 0 ? gap * perWidth : zero;  // 0 for the nearest plane; inf, not NaN, where 1 / (c d) overflows
    const V p = -(ax * planes.nx[k] + ay * planes.ny[k] + az * planes.nz[k]);
    const V coefficient = -6.0 * t * (one - t) * ((p > 0 ? p : zero) - mean);
    // s'(t_k) (P_k - mean) d grad t_k, d grad t_k = (n_1 - n_k) / c + t_k n_1; 0 from t_k = 1 on
    // (selected after the products: t_k may be inf there).
    const V sx = coefficient * ((n1x - planes.nx[k]) * (1.0 / c) + t * n1x);
    const V sy = coefficient * ((n1y - planes.ny[k]) * (1.0 / c) + t * n1y);
    const V sz = coefficient * ((n1z - planes.nz[k]) * (1.0 / c) + t * n1z);
    gx += t < 1.0 ? sx : zero;
    gy += t < 1.0 ? sy : zero;
    gz += t < 1.0 ? sz : zero;
  }
  const V scale = share / weights;
  out.area = share * mean;
  out.slopeX = gx * scale;
  out.slopeY = gy * scale;
  out.slopeZ = gz * scale;
}

}  // namespace tessera

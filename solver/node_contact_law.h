#pragma once
// The contact law of one node contact, inline, for the loops that run it in SIMD lanes
// (solver/contact_law.cpp, solver/pair_contacts.cpp). Only for files compiled as the solver
// library is, without floating-point contraction: elsewhere a compiler may fuse multiply-adds and
// give other bits. The law itself: solver/contact_law.h, docs/physics.md "Contact law".
#include "solver/contact_parameters.h"

#include <cmath>

namespace tessera {

/// The law's constants for one pair: k_n a = perNodeNormal + perAreaNormal a (N/m; one of the two
/// is 0), k_t a likewise, the normal viscosity (Pa s/m), mu and the step (s).
struct ContactLawConstants {
  double perNodeNormal, perAreaNormal, perNodeTangent, perAreaTangent, viscosity, friction, dt;
  static ContactLawConstants of(const ContactParameters& p, double kn, double kt, double dt) {
    const bool perNode = p.perNodeStiffness > 0;
    return {perNode ? p.perNodeStiffness : 0.0, perNode ? 0.0 : kn, perNode ? p.tangentialRatio * p.perNodeStiffness : 0.0,
            perNode ? 0.0 : kt, p.normalViscosity, p.friction, dt};
  }
};

/// The normal force of one contact: f_n = k_n a d - eta_n a v_n clipped at 0, with its elastic part
/// k_n a d, the approach speed v_n = v . n, and k_t a (0 for a node facing away, area 0).
struct NormalForce {
  double kna, kta, vn, elastic, fn;
};
__attribute__((always_inline)) inline NormalForce normalForce(const ContactLawConstants& k, double nx, double ny, double nz,
                                                              double depth, double area, double vx, double vy, double vz) {
  NormalForce f;
  const double keep = area > 0 ? 1.0 : 0.0;  // 0: facing away, no force, spring or energy
  f.kna = keep * (k.perNodeNormal + k.perAreaNormal * area);  // k_n a, or the per-node k
  f.kta = keep * (k.perNodeTangent + k.perAreaTangent * area);
  f.vn = vx * nx + vy * ny + vz * nz;
  f.elastic = f.kna * depth;
  const double pushed = f.elastic - k.viscosity * area * f.vn;
  f.fn = pushed > 0 ? pushed : 0.0;
  return f;
}

/// What the update of a contact's tangential spring dissipated: J by sliding, and 1 if it slid.
struct SpringUpdate {
  double friction, sliding;
};

/// The first part of the law for one contact: its tangential spring u, in place (normal n, depth,
/// area, relative velocity v). Without branches, so that a loop over contacts runs it in SIMD
/// lanes; every caller is compiled without floating-point contraction (the same bits everywhere).
__attribute__((always_inline)) inline SpringUpdate updateSpring(const ContactLawConstants& k, double nx, double ny,
                                                                double nz, double depth, double area, double vx,
                                                                double vy, double vz, double& ux, double& uy, double& uz) {
  const NormalForce n = normalForce(k, nx, ny, nz, depth, area, vx, vy, vz);
  // Turn the spring onto the tangent plane, keeping its length: u = (s - n (n.s)) |s| / |s - n (n.s)|
  // (a spring already in the plane is left as it is: then the ratio is exactly 1).
  const double along = nx * ux + ny * uy + nz * uz;
  const double length2 = ux * ux + uy * uy + uz * uz;
  double tx = ux - along * nx, ty = uy - along * ny, tz = uz - along * nz;
  const double projected2 = tx * tx + ty * ty + tz * tz;
  const double ratio = length2 / (projected2 > 0 ? projected2 : 1.0);  // every operation in every lane:
  const double turn = std::sqrt(projected2 > 0 ? ratio : 1.0);           // then the lanes choose
  tx *= turn;
  ty *= turn;
  tz *= turn;
  // u = turned + v_t dt; the trial force -k_t a u.
  const double dx = (vx - n.vn * nx) * k.dt, dy = (vy - n.vn * ny) * k.dt, dz = (vz - n.vn * nz) * k.dt;
  double sx = tx + dx, sy = ty + dy, sz = tz + dz;
  const double ftx = -n.kta * sx, fty = -n.kta * sy, ftz = -n.kta * sz;
  const double cap = k.friction * n.fn, ft2 = ftx * ftx + fty * fty + ftz * ftz;
  // Sliding: u scaled back to the Coulomb cap, |k_t a u| = mu f_n. Dissipated: the work put into
  // the spring over the increment (trapezoidal, as a sticking spring stores it exactly) less what
  // it now stores: k_t a (u_0 + u) / 2 . du - k_t a (|u|^2 - |u_0|^2) / 2.
  const bool slides = ft2 > cap * cap;
  const double capped = cap / std::sqrt(ft2 > 0 ? ft2 : 1.0);
  const double scale = slides ? capped : 1.0;
  sx *= scale;
  sy *= scale;
  sz *= scale;
  const double u2 = sx * sx + sy * sy + sz * sz, turned2 = tx * tx + ty * ty + tz * tz;
  const double work = 0.5 * ((tx + sx) * dx + (ty + sy) * dy + (tz + sz) * dz);
  const double keep = area > 0 ? 1.0 : 0.0;
  ux = keep * sx;
  uy = keep * sy;
  uz = keep * sz;
  return {slides ? n.kta * (work - 0.5 * (u2 - turned2)) : 0.0, slides ? 1.0 : 0.0};
}

/// What one node contact gives with its spring updated (updateSpring): its force on the node's
/// body f = f_n n - k_t a u (N), f_n (N), its stored energy 1/2 k_n a d^2 + 1/2 k_t a |u|^2 (J) and
/// what the normal viscosity dissipated this step, (k_n a d - f_n) v_n dt (J).
struct ContactForce {
  double fx, fy, fz, fn, stored, viscous;
};
__attribute__((always_inline)) inline ContactForce contactForce(const ContactLawConstants& k, double nx, double ny,
                                                                double nz, double depth, double area, double vx,
                                                                double vy, double vz, double ux, double uy, double uz) {
  const NormalForce n = normalForce(k, nx, ny, nz, depth, area, vx, vy, vz);
  ContactForce f;
  f.fn = n.fn;
  f.fx = n.fn * nx - n.kta * ux;
  f.fy = n.fn * ny - n.kta * uy;
  f.fz = n.fn * nz - n.kta * uz;
  f.stored = 0.5 * n.elastic * depth + 0.5 * n.kta * (ux * ux + uy * uy + uz * uz);
  // The non-elastic part of the normal force, f_n - k_n a d, does the work (f_n - k_n a d) v_n dt.
  f.viscous = (n.elastic - n.fn) * n.vn * k.dt;
  return f;
}

}  // namespace tessera

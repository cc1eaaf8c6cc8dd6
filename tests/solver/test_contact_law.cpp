// The contact law over a batch (solver/contact_law.h) against its equations, entry by entry: a
// sticking spring, Coulomb sliding with the energy it dissipates, a spring turned onto a new
// tangent plane, a node facing away, and lanes that do not affect each other.
#include "solver/contact_law.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

using namespace tessera;

namespace {

// One batch's storage.
struct Contacts {
  std::vector<ContactReal> nx, ny, nz, depth, area, vx, vy, vz, ux, uy, uz, fx, fy, fz, fn, stored, friction, viscous, sliding;
  explicit Contacts(int n) {
    for (auto* v : {&nx, &ny, &nz, &depth, &area, &vx, &vy, &vz, &ux, &uy, &uz, &fx, &fy, &fz, &fn, &stored, &friction,
                    &viscous, &sliding})
      v->assign(static_cast<std::size_t>(n), ContactReal(0));
  }
  NodeContactBatch batch() {
    return {static_cast<int>(depth.size()), nx.data(), ny.data(), nz.data(), depth.data(), area.data(), vx.data(), vy.data(),
            vz.data(), ux.data(), uy.data(), uz.data(), fx.data(), fy.data(), fz.data(), fn.data(), stored.data(),
            friction.data(), viscous.data(), sliding.data()};
  }
};

constexpr double kn = 5e11, kt = 5e11, dt = 1e-6;  // N/m^3, s
// The law runs in ContactReal (float): each input is rounded once, and each result is a few
// operations away from them, so it agrees with the equation in double to a few float roundings.
constexpr double kRounding = 1e-6;

}  // namespace

TEST_CASE("contact law: sticking, f_n = k_n a d and f_t = -k_t a u with u = v_t dt, stored energy is their half products") {
  ContactParameters p;
  Contacts c(1);
  const double a = 1e-7, d = 1e-7, vt = 2e-3;
  c.nz[0] = 1;
  c.depth[0] = d;
  c.area[0] = a;
  c.vx[0] = vt;
  applyContactLaw(p, kn, kt, dt, c.batch());
  const double u = vt * dt;
  CHECK(c.fn[0] == Approx(kn * a * d).epsilon(kRounding));
  CHECK(c.fz[0] == Approx(kn * a * d).epsilon(kRounding));
  CHECK(c.fx[0] == Approx(-kt * a * u).epsilon(kRounding));
  CHECK(c.ux[0] == Approx(u).epsilon(kRounding));
  CHECK(c.sliding[0] == 0);
  CHECK(c.friction[0] == 0);
  CHECK(c.stored[0] == Approx(0.5 * kn * a * d * d + 0.5 * kt * a * u * u).epsilon(kRounding));
}

TEST_CASE("contact law: past mu f_n the spring is cut back to the Coulomb cap and the energy it loses is dissipated") {
  ContactParameters p;
  p.friction = 0.23;
  Contacts c(1);
  const double a = 1e-7, d = 1e-7, s = 1e-6;  // a spring 10x the depth: far past the cap
  c.nz[0] = 1;
  c.depth[0] = d;
  c.area[0] = a;
  c.uy[0] = s;
  applyContactLaw(p, kn, kt, dt, c.batch());
  const double fn = kn * a * d, capped = p.friction * fn / (kt * a);  // the spring at the cap
  CHECK(c.sliding[0] == 1);
  CHECK(std::hypot(c.fx[0], c.fy[0]) == Approx(p.friction * fn).epsilon(kRounding));
  CHECK(c.fy[0] < 0);  // against the spring
  CHECK(c.uy[0] == Approx(capped).epsilon(kRounding));
  // No increment (at rest): the dissipated energy is the spring energy lost, k_t a (s^2 - u^2) / 2.
  CHECK(c.friction[0] == Approx(0.5 * kt * a * (s * s - capped * capped)).epsilon(kRounding));
}

TEST_CASE("contact law: a spring out of the tangent plane is turned onto it with its length kept") {
  ContactParameters p;
  p.friction = 1e9;  // no sliding
  Contacts c(1);
  const double s = 1e-8;
  c.nz[0] = 1;
  c.depth[0] = 1e-7;
  c.area[0] = 1e-7;
  c.ux[0] = s / std::sqrt(2.0);
  c.uz[0] = s / std::sqrt(2.0);
  applyContactLaw(p, kn, kt, dt, c.batch());
  CHECK(c.uz[0] == 0);
  CHECK(c.ux[0] == Approx(s).epsilon(kRounding));
}

TEST_CASE("contact law: a node facing away (area 0) gets no force, spring or energy, also with a per-node stiffness") {
  for (const double perNode : {0.0, 1e4}) {
    ContactParameters p;
    p.perNodeStiffness = perNode;
    Contacts c(1);
    c.nz[0] = 1;
    c.depth[0] = 1e-7;
    c.area[0] = 0;
    c.ux[0] = 1e-8;
    c.vx[0] = 1e-3;
    applyContactLaw(p, kn, kt, dt, c.batch());
    CHECK(c.fx[0] == 0);
    CHECK(c.fz[0] == 0);
    CHECK(c.ux[0] == 0);
    CHECK(c.stored[0] == 0);
    CHECK(c.friction[0] == 0);
  }
}

TEST_CASE("contact law: entries are independent: a batch of many gives each the bits it gets alone") {
  ContactParameters p;
  p.normalViscosity = 1e3;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  const int n = 37;  // not a multiple of any vector width
  Contacts all(n);
  for (int i = 0; i < n; ++i) {
    double x = unit(random), y = unit(random), z = unit(random);
    const double norm = std::sqrt(x * x + y * y + z * z);
    all.nx[i] = x / norm;
    all.ny[i] = y / norm;
    all.nz[i] = z / norm;
    all.depth[i] = 1e-7 * (1 + unit(random));
    all.area[i] = i % 5 == 0 ? 0.0 : 1e-7 * (1 + unit(random));
    all.vx[i] = 1e-2 * unit(random);
    all.vy[i] = 1e-2 * unit(random);
    all.vz[i] = 1e-2 * unit(random);
    all.ux[i] = 1e-7 * unit(random);
    all.uy[i] = 1e-7 * unit(random);
    all.uz[i] = 1e-7 * unit(random);
  }
  Contacts before = all;
  applyContactLaw(p, kn, kt, dt, all.batch());
  for (int i = 0; i < n; ++i) {
    Contacts one(1);
    for (auto [to, from] : {std::pair{&one.nx, &before.nx}, {&one.ny, &before.ny}, {&one.nz, &before.nz}, {&one.depth, &before.depth},
                            {&one.area, &before.area}, {&one.vx, &before.vx}, {&one.vy, &before.vy}, {&one.vz, &before.vz},
                            {&one.ux, &before.ux}, {&one.uy, &before.uy}, {&one.uz, &before.uz}})
      (*to)[0] = (*from)[static_cast<std::size_t>(i)];
    applyContactLaw(p, kn, kt, dt, one.batch());
    INFO("entry " << i);
    CHECK(one.fx[0] == all.fx[i]);
    CHECK(one.fy[0] == all.fy[i]);
    CHECK(one.fz[0] == all.fz[i]);
    CHECK(one.ux[0] == all.ux[i]);
    CHECK(one.stored[0] == all.stored[i]);
    CHECK(one.friction[0] == all.friction[i]);
    CHECK(one.viscous[0] == all.viscous[i]);
  }
}

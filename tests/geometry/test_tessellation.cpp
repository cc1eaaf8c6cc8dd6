// The built-in square tessellation and its interlocking span.
#include "io/input_error.h"
#include "geometry/tessellation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace tessera;

TEST_CASE("the paper's slab: 7 x 7 at 10 mm, outer ring of 24 fixed, checkerboard of 90-degree turns") {
  SquareGridOptions o;  // defaults are the paper's
  const auto grid = squareGrid(o, "planar");
  REQUIRE(grid.size() == 49);
  REQUIRE(std::count_if(grid.begin(), grid.end(), [](const Placement& p) { return p.fixed; }) == 24);
  for (const Placement& p : grid) {
    const int r = std::stoi(p.name.substr(1, p.name.find('c') - 1)), c = std::stoi(p.name.substr(p.name.find('c') + 1));
    REQUIRE(p.translation.x() == Approx((c - 3) * 10e-3).margin(1e-15));
    REQUIRE(p.translation.y() == Approx((r - 3) * 10e-3).margin(1e-15));
    const double turn = 2 * std::atan2(p.rotation.z(), p.rotation.w());
    REQUIRE(turn == Approx((r + c) % 2 ? M_PI / 2 : 0.0).margin(1e-15));
    REQUIRE(p.fixed == (r == 0 || c == 0 || r == 6 || c == 6));
  }
  const InterlockingSpan span = squareGridSpan(o);
  REQUIRE(span.interfaces == 6);
  REQUIRE(span.length == Approx(50e-3).epsilon(1e-12));
}

TEST_CASE("square tessellation options: gap widens the pitch, no perimeter, no alternation") {
  SquareGridOptions o;
  o.columns = 4;
  o.rows = 3;
  o.gap = 0.5e-3;
  o.alternate = false;
  o.fixPerimeter = false;
  const auto grid = squareGrid(o, "b");
  REQUIRE(grid.size() == 12);
  REQUIRE((grid[1].translation - grid[0].translation).norm() == Approx(10.5e-3).epsilon(1e-12));
  for (const Placement& p : grid) {
    REQUIRE_FALSE(p.fixed);
    REQUIRE(p.rotation.angularDistance(Eigen::Quaterniond::Identity()) == 0.0);
  }
  REQUIRE(squareGridSpan(o).interfaces == 0);
  o.pitch = -1;
  REQUIRE_THROWS_AS(squareGrid(o, "b"), InputError);
}

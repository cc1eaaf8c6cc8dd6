// Layout files: what they accept, and every kind of bad layout refused with the file and the reason.
#include "io/input_error.h"
#include "levelset/layout_file.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

std::string layoutText(const std::string& bodies, const std::string& extra = "") {
  return R"({"format": "tessera-layout", "version": 1, "unit": "mm",
             "shapes": {"b": {"mesh": "block.obj", "spacing": 0.5}}, )" +
         extra + R"("bodies": [)" + bodies + "]}";
}

Layout readText(const test::TempDir& dir, const std::string& text) {
  test::writeFile(dir / "layout.json", text);
  return readLayout(dir / "layout.json");
}

}  // namespace

TEST_CASE("a layout file gives placements in metres with resolved paths") {
  test::TempDir dir;
  const Layout l = readText(dir, layoutText(R"({"name": "a", "shape": "b", "position": [1, 2, 3], "fixed": true},
                                               {"name": "c", "shape": "b", "position": [11, 2, 3], "rotate_z_deg": 90},
                                               {"name": "d", "shape": "b", "position": [0, 0, 0], "quaternion": [0, 0, 0, 1]})",
                                            R"("span": {"length": 50, "interfaces": 6}, )"));
  REQUIRE(l.bodies.size() == 3);
  REQUIRE(l.shapes.size() == 1);
  REQUIRE(l.shapes[0].mesh == dir / "block.obj");
  REQUIRE(*l.shapes[0].spacing == Approx(0.5e-3));
  REQUIRE(l.bodies[0].translation.isApprox(Eigen::Vector3d(1e-3, 2e-3, 3e-3)));
  REQUIRE(l.bodies[0].fixed);
  REQUIRE_FALSE(l.bodies[1].fixed);
  REQUIRE((l.bodies[1].rotation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-15);
  REQUIRE(std::abs(l.bodies[2].rotation.z()) == 1.0);
  REQUIRE(l.spanInterfaces == 6);
  REQUIRE(l.spanLength == Approx(50e-3));
}

TEST_CASE("bad layouts are refused naming the file and the problem") {
  test::TempDir dir;
  const auto refused = [&](const std::string& text, const std::string& problem) {
    INFO(text);
    REQUIRE_THROWS_WITH(readText(dir, text), Contains("layout.json") && Contains(problem));
  };
  const std::string body = R"({"name": "a", "shape": "b", "position": [0, 0, 0]})";
  refused(layoutText(""), "bodies: missing or empty");
  refused(layoutText(body + "," + body), "body 'a': duplicate name");
  refused(layoutText(R"({"name": "a", "shape": "nope", "position": [0, 0, 0]})"), "unknown shape 'nope'");
  refused(layoutText(R"({"name": "a", "shape": "b", "position": [0, 0, 0], "quaternion": [1, 1, 0, 0]})"),
          "norm 1.414214, not 1");
  refused(layoutText(R"({"name": "a", "shape": "b", "position": [0, NaN, 0]})"), "not valid JSON");
  refused(layoutText(R"({"name": "a", "shape": "b", "position": [0, "NaN", 0]})"), "numbers only");
  refused(layoutText(R"({"name": "a", "shape": "b", "position": [0, 1e999, 0]})"), "not valid JSON");  // fuzz_layout
  refused(layoutText(R"({"name": "a", "shape": "b", "position": [0, 0]})"), "array of 3 numbers");
  refused(layoutText(R"({"name": "a", "shape": "b", "position": [0, 0, 0], "colour": "red"})"), "unknown key 'colour'");
  refused(R"({"format": "tessera-layout", "version": 2})", "version: must be 1");
  refused(R"({"format": "tessera-layout", "version": 4294967297})", "version: must be 1");  // not wrapped to 1
  refused(layoutText(body, R"("span": {"length": 50, "interfaces": 4294967297}, )"), "from 1 to 1000000");
  refused(R"({"format": ["tessera-layout"], "version": 1})", "format: must be \"tessera-layout\"");  // found by fuzz_layout
  refused(R"({"format": "tessera-layout", "version": 1, "unit": "parsec", "shapes": {}, "bodies": []})",
          "unknown length unit 'parsec'");
  REQUIRE_THROWS_WITH(readLayout(dir / "missing.json"), Contains("missing.json") && Contains("cannot open"));
}

// tessera block: write a parametric block mesh (OBJ or STL).
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "geometry/length_unit.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_export.h"
#include "geometry/mesh_validation.h"
#include "tools/commands.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

namespace tessera::tools {

namespace {

struct BlockArguments {
  std::string family;
  std::string unit;
  std::string output;
  double size = 10;         // in --unit: side a (planar, wave, box, osteomorphic) or inradius r (hex)
  std::optional<double> width;  // in --unit: side b of box and osteomorphic [default: size]
  double thickness = 3.18;  // in --unit
  double angle = 5;         // degrees
  std::optional<double> amplitude;  // in --unit (wave, osteomorphic) [default: kDefaultAmplitudePerSize x size]
  double amplitudeY = 0;    // in --unit (osteomorphic)
  int waves = 1;            // wave
  int levels = 0;           // 0: the family's default, wave 24, osteomorphic 12
  bool ascii = false;
};

// Every length and angle checked as it comes in: a block of 1 um to 1 km with a finite angle below
// 90 degrees ("--size inf" wrote infinite vertices; "--width -3" was silently replaced by --size).
void checkBlockArguments(const BlockArguments& a, double metres) {
  const auto length = [&](const char* flag, double value, bool zeroAllowed) {
    if (zeroAllowed && value == 0) return;
    if (!(std::abs(value) * metres >= 1e-6 && std::abs(value) * metres <= 1e3) || (!zeroAllowed && value < 0)) {
      std::ostringstream m;
      m << flag << " = " << value << " " << a.unit << " is not a " << (zeroAllowed ? "" : "positive ")
        << "length of 1 um to 1 km; give it in --unit " << a.unit;
      throw InputError(m.str());
    }
  };
  length("--size", a.size, false);
  length("--thickness", a.thickness, false);
  if (a.width) length("--width", *a.width, false);
  if (a.amplitude) length("--amplitude", *a.amplitude, true);
  length("--y-amplitude", a.amplitudeY, true);
  if (!(a.angle >= 0 && a.angle < 90))
    throw InputError("--angle = " + std::to_string(a.angle) + " must be at least 0 and below 90 degrees");
}

void runBlock(const BlockArguments& a) {
  const LengthUnit unit = parseLengthUnit(a.unit);
  checkBlockArguments(a, unit.metres);
  const double m = unit.metres, theta = a.angle * M_PI / 180, width = a.width ? *a.width : a.size;
  const double amplitude = a.amplitude ? *a.amplitude : kDefaultAmplitudePerSize * a.size;
  if (a.amplitudeY != 0 && a.family != "osteomorphic")
    throw InputError("--y-amplitude applies to the osteomorphic family only; leave it out for " + a.family);
  TriangleMesh mesh;
  if (a.family == "planar") mesh = makePlanarBlock(a.size * m, a.thickness * m, theta);
  else if (a.family == "box") mesh = makeBox(a.size * m, width * m, a.thickness * m);
  else if (a.family == "wave")
    mesh = makeWaveBlock(a.size * m, a.thickness * m, theta, amplitude * m, a.waves, a.levels != 0 ? a.levels : 24);
  else if (a.family == "osteomorphic")
    mesh = makeOsteomorphicBlock(a.size * m, width * m, a.thickness * m, amplitude * m,
                                 a.amplitudeY * m, a.levels != 0 ? a.levels : 12);
  else if (a.family == "hex") mesh = makeHexBlock(a.size * m, a.thickness * m, theta);
  else throw InputError("unknown block family '" + a.family + "'; use planar, box, wave, osteomorphic or hex");

  validateSolidMesh(mesh, a.family + " block");  // generators must give valid solids; refuse loudly if not
  MeshFileFormat format = meshFormatFromPath(a.output);
  if (format == MeshFileFormat::StlBinary && a.ascii) format = MeshFileFormat::StlAscii;
  const std::filesystem::path parent = std::filesystem::path(a.output).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  writeMesh(mesh, a.output, format, m);
  const MassProperties p = computeMassProperties(mesh);
  const Eigen::Vector3d size = boundingBox(mesh.vertices).sizes() / m;
  std::printf("%s block: %zu triangles, %.6g x %.6g x %.6g %s, volume %.9g %s^3\nwritten to %s (unit %s)\n",
              a.family.c_str(), mesh.triangles.size(), size.x(), size.y(), size.z(), unit.name.c_str(),
              p.volume / (m * m * m), unit.name.c_str(), a.output.c_str(), unit.name.c_str());
}

}  // namespace

void addBlockCommand(CLI::App& app) {
  auto args = std::make_shared<BlockArguments>();
  CLI::App* cmd = app.add_subcommand("block", "Write a parametric block mesh (closed, outward-oriented) as OBJ or STL.");
  cmd->add_option("family", args->family,
                  "planar: TIS block with faces at +-angle; box; wave: planar block with corrugated faces; "
                  "osteomorphic: box with matching curved x-faces (tile with --no-alternate); hex: hexagonal TIS block")
      ->required()
      ->check(CLI::IsMember({"planar", "box", "wave", "osteomorphic", "hex"}));
  cmd->add_option("--unit", args->unit, "Length unit of the lengths given and of the file written: m, cm, mm, um, in, ft")
      ->required();
  cmd->add_option("-o,--output", args->output, "Mesh file to write: .obj or .stl (binary unless --ascii)")->required();
  cmd->add_option("--size", args->size, "Side a of the square mid-section (planar, wave), side along x (box, osteomorphic), or inradius r (hex), in --unit")
      ->capture_default_str();
  cmd->add_option("--width", args->width, "box and osteomorphic: side b along y, in --unit [default: --size]");
  cmd->add_option("--thickness", args->thickness, "Thickness h, in --unit")->capture_default_str();
  cmd->add_option("--angle", args->angle, "Inclination theta of the lateral faces, degrees")->capture_default_str();
  cmd->add_option("--amplitude", args->amplitude,
                  "wave and osteomorphic: amplitude A of the curved faces (osteomorphic: the x-faces), in --unit "
                  "[default: 0.02 x --size]");
  cmd->add_option("--y-amplitude", args->amplitudeY,
                  "osteomorphic: amplitude of the y-faces, curved like the x-faces so that the block interlocks with "
                  "all four neighbours, in --unit [default: 0, flat y-faces]");
  cmd->add_option("--waves", args->waves, "wave only: full waves n across the thickness")->capture_default_str();
  cmd->add_option("--levels", args->levels, "Mesh resolution. wave: flat segments across the thickness [24]; osteomorphic: segments per "
                  "half-wave [12]")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));  // the upper limits: the generators
  cmd->add_flag("--ascii", args->ascii, "Write ASCII STL instead of binary");
  cmd->footer("Example: tessera block planar --size 10 --thickness 3.18 --angle 5 --unit mm -o planar.obj");
  cmd->callback([args] { runBlock(*args); });
}

}  // namespace tessera::tools

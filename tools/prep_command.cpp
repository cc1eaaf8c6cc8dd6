// tessera prep: mesh file -> validated, measured, solver-ready shape in an asset bundle.
#include "io/input_error.h"
#include "geometry/length_unit.h"
#include "levelset/bundle.h"
#include "levelset/bundle_edit.h"
#include "levelset/shape_builder.h"
#include "tools/commands.h"
#include "tools/resolution_options.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

namespace tessera::tools {

namespace fs = std::filesystem;

namespace {

struct PrepArguments {
  std::string mesh;
  std::string unit;
  std::string output;
  std::string name;
  std::string up = "z";
  ResolutionArguments resolution;
  double featureAngle = 30;  // deg
  int band = 3;              // voxels
  bool replace = false;
};

void runPrep(const PrepArguments& a) {
  const auto start = std::chrono::steady_clock::now();
  const LengthUnit unit = parseLengthUnit(a.unit);
  ShapeResolution resolution = shapeResolution(a.resolution, unit.metres, a.mesh);
  resolution.featureAngle = a.featureAngle * M_PI / 180.0;
  resolution.exteriorBandVoxels = a.band;
  if (!(a.featureAngle > 0 && a.featureAngle < 180)) throw InputError("--feature-angle must be between 0 and 180 degrees");

  ShapeRequest request{a.mesh, a.unit, a.name, resolution, shapeLimits(a.resolution), a.up};
  PrepLog log;
  log.now = [](const std::string& m) { std::cerr << "prep: " << m << "\n"; };
  std::cerr << "prep: reading " << a.mesh << " (unit " << unit.name << (a.up == "z" ? "" : ", up axis " + a.up + " turned to +z") << ")\n";
  const Shape s = prepareIntoBundle(request, a.output, a.replace, log);
  for (const auto& note : log.notes) std::cerr << "prep: note: " << note << "\n";
  for (const auto& warning : log.warnings) std::cerr << "prep: warning: " << warning << "\n";

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("shape '%s' from %s\n", s.name.c_str(), a.mesh.c_str());
  std::printf("  volume        %.6g mm^3\n", s.mass.volume * 1e9);
  std::printf("  surface area  %.6g mm^2\n", s.mass.surfaceArea * 1e6);
  std::printf("  nodes         %zu (spacing %.4g mm, %.4g mm at sharp edges)\n", s.nodes.size(),
              s.resolution.nodeSpacing * 1e3, s.resolution.edgeSpacingFraction * s.resolution.nodeSpacing * 1e3);
  std::printf("  grid          %d x %d x %d (voxel %.4g mm)\n", s.sdf.dims[0], s.sdf.dims[1], s.sdf.dims[2],
              s.sdf.voxelSize * 1e3);
  std::printf("  level set     %s\n", levelSetPath(s).c_str());
  std::printf("written to %s (%s, %s.vdb) in %.2f s\n", a.output.c_str(), kBundleFileName, s.name.c_str(), seconds);
}

}  // namespace

void addPrepCommand(CLI::App& app) {
  auto args = std::make_shared<PrepArguments>();
  CLI::App* cmd = app.add_subcommand(
      "prep", "Turn a block mesh (STL/OBJ) into a validated level-set shape in an asset bundle (created or added to).");
  cmd->add_option("mesh", args->mesh, "Closed triangle mesh of one block: STL (ASCII or binary) or OBJ")->required();
  cmd->add_option("--unit", args->unit, "Length unit of the mesh file: m, cm, mm, um, in, ft (files carry none)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Bundle directory to create or add to (bundle.h5 + <name>.vdb)")->required();
  addResolutionOptions(*cmd, args->resolution);
  cmd->add_option("--feature-angle", args->featureAngle,
                  "Edges whose faces bend more than this are sharp and get edge nodes, degrees")
      ->capture_default_str();
  cmd->add_option("--band", args->band, "Exterior band (and grid padding) outside the surface, voxels")
      ->capture_default_str();
  cmd->add_option("--up", args->up, "The mesh's up axis (x, y or z), turned into +z (the slab's thickness)")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->capture_default_str();
  cmd->add_option("--name", args->name, "Shape name in the bundle [default: the mesh file name without extension]");
  cmd->add_flag("--replace", args->replace, "Replace a shape of the same name already in the bundle");
  cmd->footer("Example: tessera prep block.stl --unit mm -o out/slab\n"
              "Refuses open, non-manifold, self-intersecting or flat meshes with the reason; re-orients inside-out ones.");
  cmd->callback([args] { runPrep(*args); });
}

}  // namespace tessera::tools

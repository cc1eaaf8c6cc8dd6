// tessera tile: blocks + a tessellation (built-in square grid or a layout file) -> a slab bundle.
#include "io/input_error.h"
#include "geometry/length_unit.h"
#include "levelset/generated_slab.h"
#include "levelset/slab_plan.h"
#include "levelset/tiler.h"
#include "levelset/assembly_checks.h"
#include "tools/assembly_report.h"
#include "tools/commands.h"
#include "tools/resolution_options.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
namespace tessera::tools {


namespace {

struct TileArguments {
  std::string block;
  std::string layout;
  std::string tiling;
  std::optional<double> thickness;
  double angle = 5;
  unsigned seed = 1;
  std::string surface = "plane";
  double radius = 0;
  std::string unit;
  std::string up = "z";
  std::string grid = "7x7";
  std::optional<double> pitch;
  std::string fix = "perimeter";
  bool noAlternate = false;
  double gap = 0;
  std::optional<double> overlapTolerance;
  ResolutionArguments resolution;
  bool replace = false;
  std::string output;
  long maxBodies = 10000;
};

// Columns x rows, each at least 1, and at most maxBodies blocks in all (tiling's checks grow as
// the square of the count).
std::pair<int, int> parseGrid(const std::string& text, long maxBodies) {
  long long columns = 0, rows = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%lld%c%lld%c", &columns, &x, &rows, &extra) != 3 || (x != 'x' && x != 'X') ||
      columns < 1 || rows < 1)
    throw InputError("--grid '" + text + "': give columns x rows, e.g. --grid 7x7");
  if (columns > maxBodies || rows > maxBodies || columns * rows > maxBodies)
    throw InputError("--grid '" + text + "': more than --max-bodies " + std::to_string(maxBodies) +
                     " blocks; give a smaller grid, or raise --max-bodies if you mean it (tiling time grows as the square of the count)");
  return {static_cast<int>(columns), static_cast<int>(rows)};
}

// The blocks of a tiling (--tiling), each shape prepared once.
Bundle slabFromTiling(const TileArguments& a, PrepLog& log) {
  if (a.unit.empty()) throw InputError("--tiling: state the length unit of --pitch and --thickness with --unit (mm, cm, m, in)");
  if (!a.thickness) throw InputError("--tiling needs --thickness: the blocks' thickness, in --unit");
  const double m = parseLengthUnit(a.unit).metres;
  GeneratedSlabOptions options;
  if (isTilingKind(a.tiling)) {
    if (!a.pitch) throw InputError("--tiling " + a.tiling + " needs --pitch: the distance between neighbouring tile centres, in --unit");
    options.tiling.kind = a.tiling;
    std::tie(options.tiling.columns, options.tiling.rows) = parseGrid(a.grid, a.maxBodies);
    options.tiling.pitch = *a.pitch * m;
    options.tiling.seed = a.seed;
  } else {
    options.tilingFile = a.tiling;
    options.metresPerUnit = m;
    options.up = a.up;
  }
  options.thickness = *a.thickness * m;
  if (!(a.angle >= 0 && a.angle < 90)) throw InputError("--angle " + std::to_string(a.angle) + ": give the faces' tilt in degrees, in [0, 90)");
  options.angle = a.angle * M_PI / 180;
  options.surface = baseSurface(a.surface, a.radius * m, m, a.up);
  if (a.fix != "perimeter" && a.fix != "none") throw InputError("--fix '" + a.fix + "': use perimeter or none");
  options.fixPerimeter = a.fix == "perimeter";
  if (options.tilingFile.empty() && static_cast<long>(options.tiling.columns) * options.tiling.rows * (a.tiling == "rhombille" ? 3 : 1) > a.maxBodies)
    throw InputError("--grid " + a.grid + ": more than --max-bodies " + std::to_string(a.maxBodies) + " tiles; raise --max-bodies if you mean it");
  AssembleReport report;
  Bundle bundle = generatedSlab(options, a.unit, shapeResolution(a.resolution, m, a.tiling), shapeLimits(a.resolution), log, report);
  std::cerr << "tile: span " << report.spanRule << "\n";
  return bundle;
}

// Checks the assembly, then writes it and prints the summary (nothing is written if a check fails).
void writeCheckedSlab(const TileArguments& a, const Bundle& bundle, const PrepLog& log, double metresPerUnit,
                      const std::string& isolatedHint, std::chrono::steady_clock::time_point start) {
  for (const auto& note : log.notes) std::cerr << "tile: note: " << note << "\n";
  for (const auto& warning : log.warnings) std::cerr << "tile: warning: " << warning << "\n";
  const AssemblySummary summary =
      checkAssemblyBeforeWriting(bundle, a.overlapTolerance ? std::optional<double>(*a.overlapTolerance * metresPerUnit) : std::nullopt,
                                 a.gap * metresPerUnit, "check --pitch or the layout positions, or add --gap", isolatedHint, true);
  writeBundle(a.output, bundle);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printAssemblySummary(bundle, summary, "tile");
  printAssemblyVerdict(bundle, a.output);
  std::printf("written to %s in %.2f s\n", a.output.c_str(), seconds);
}

void runTile(const TileArguments& a) {
  const auto start = std::chrono::steady_clock::now();
  if (a.block.empty() + a.layout.empty() + a.tiling.empty() != 2)
    throw InputError("give one of --block MESH (with --grid and --pitch), --layout FILE or --tiling NAME|FILE");
  checkBundleOutput(a.output, a.replace);
  if (!a.tiling.empty()) {
    PrepLog log;
    log.now = [](const std::string& m) { std::cerr << "tile: " << m << "\n"; };
    const Bundle bundle = slabFromTiling(a, log);
    writeCheckedSlab(a, bundle, log, parseLengthUnit(a.unit).metres, "check --pitch, --thickness and --angle", start);
    return;
  }

  SlabPlan plan;
  if (!a.block.empty()) {
    if (a.unit.empty()) throw InputError(a.block + ": state the mesh's length unit with --unit (mm, cm, m, in)");
    if (!a.pitch) throw InputError("--pitch is required with --block: the centre-to-centre distance, in --unit");
    const double m = parseLengthUnit(a.unit).metres;
    SquareGridOptions grid;
    std::tie(grid.columns, grid.rows) = parseGrid(a.grid, a.maxBodies);
    grid.pitch = *a.pitch * m;
    grid.gap = a.gap * m;
    grid.alternate = !a.noAlternate;
    if (a.fix != "perimeter" && a.fix != "none") throw InputError("--fix '" + a.fix + "': use perimeter or none");
    grid.fixPerimeter = a.fix == "perimeter";
    plan = gridSlabPlan(a.block, a.unit, grid, a.up);
  } else {
    plan = layoutSlabPlan(a.layout, a.maxBodies);
    plan.up = a.up;
    if (!a.unit.empty() && a.unit != plan.unit)
      throw InputError(a.layout + ": the layout states unit '" + plan.unit + "'; drop --unit or make them agree");
  }
  for (const std::string& note : plan.notes) std::cerr << "tile: note: " << note << "\n";
  const std::string& unitName = plan.unit;
  const LengthUnit unit = parseLengthUnit(unitName);
  const ShapeResolution resolution = shapeResolution(a.resolution, unit.metres, a.block.empty() ? a.layout : a.block);

  PrepLog log;
  log.now = [](const std::string& m) { std::cerr << "tile: " << m << "\n"; };
  const Bundle bundle = tileSlab(plan, resolution, log, shapeLimits(a.resolution));
  writeCheckedSlab(a, bundle, log, unit.metres,
                   (a.block.empty() ? std::string("check the layout's positions and unit") : std::string("check that --pitch is in the block's unit (--unit)")) +
                       " and that the blocks' thickness is along z (--up y for y-up meshes)",
                   start);
}

}  // namespace

void addTileCommand(CLI::App& app) {
  auto args = std::make_shared<TileArguments>();
  CLI::App* cmd = app.add_subcommand("tile", "Lay blocks out in a tessellation and write the slab's bundle (shapes + bodies).");
  cmd->add_option("--block", args->block, "Block mesh (STL/OBJ) for the built-in square tessellation");
  cmd->add_option("--layout", args->layout, "Layout file (JSON, docs/tiling.md) of arbitrary placements, instead of --block");
  cmd->add_option("--tiling", args->tiling,
                  "Generate the blocks from a tiling: square, hex, triangle, rhombille, voronoi, or a polygon mesh file (OBJ) of the tiles; instead of --block");
  cmd->add_option("--thickness", args->thickness, "With --tiling: the blocks' thickness, in --unit");
  cmd->add_option("--angle", args->angle, "With --tiling: the tilt of the blocks' side faces, degrees (a tiling file's edges drawn as lines in a group angle_<degrees> take that angle)")->capture_default_str();
  cmd->add_option("--seed", args->seed, "With --tiling voronoi: the seed of the random sites")->capture_default_str();
  cmd->add_option("--surface", args->surface,
                  "With --tiling: lay the tiles on a plane, a sphere (a dome), a cylinder along x (a barrel vault), or the surface of "
                  "a mesh FILE (STL, OBJ, PLY in --unit: a height field over the plan, as a design tool exports a roof)")
      ->capture_default_str();
  cmd->add_option("--radius", args->radius, "With --surface sphere or cylinder: its radius, in --unit");
  cmd->add_option("--unit", args->unit, "Length unit of the mesh and of every length given: m, cm, mm, um, in, ft");
  cmd->add_option("--up", args->up, "The up axis (x, y or z) of the block mesh, layout, tiling file or surface file, turned into +z (the slab's thickness)")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->capture_default_str();
  cmd->add_option("--grid", args->grid, "Square tessellation: columns x rows")->capture_default_str();
  cmd->add_option("--pitch", args->pitch, "Centre-to-centre distance of neighbouring blocks (tiles sharing an edge), in --unit");
  cmd->add_option("--fix", args->fix, "Fixed blocks: perimeter (the outer ring; with --tiling, the tiles with an edge on the boundary) or none")
      ->capture_default_str();
  cmd->add_flag("--no-alternate", args->noAlternate, "Do not turn every other block by 90 degrees (checkerboard)");
  cmd->add_option("--gap", args->gap, "Clearance added between neighbouring blocks, in --unit")->capture_default_str();
  addResolutionOptions(*cmd, args->resolution);
  cmd->add_option("--overlap-tolerance", args->overlapTolerance,
                  "Initial overlap accepted between bodies, in --unit [default: 0.1 voxel]");
  cmd->add_option("-o,--output", args->output, "Bundle directory to write (bundle.h5 + one .vdb per shape)")->required();
  cmd->add_flag("--replace", args->replace, "Replace a bundle already in the output directory");
  cmd->add_option("--max-bodies", args->maxBodies, "Refuse a slab of more blocks than this")->capture_default_str();
  cmd->footer("Example (the paper's slab): tessera tile --block planar.obj --unit mm --grid 7x7 --pitch 10 --fix perimeter -o slab\n"
              "Generated: tessera tile --tiling hex --grid 7x7 --pitch 10 --thickness 3.18 --angle 5 --unit mm -o hex_slab\n"
              "A dome:    tessera tile --tiling hex --grid 9x9 --pitch 10 --thickness 3.18 --angle 5 --surface sphere --radius 500 --unit mm -o dome");
  cmd->callback([args] { runTile(*args); });
}

}  // namespace tessera::tools

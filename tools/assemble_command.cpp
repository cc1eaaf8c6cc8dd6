// tessera assemble: part meshes placed in world coordinates (a design tool's export) -> a bundle.
#include "io/input_error.h"
#include "geometry/length_unit.h"
#include "levelset/assembler.h"
#include "levelset/assembly_checks.h"
#include "tools/assembly_report.h"
#include "tools/commands.h"
#include "tools/resolution_options.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace tessera::tools {

namespace fs = std::filesystem;

namespace {

struct AssembleArguments {
  std::vector<std::string> parts;
  std::string unit, up = "z", output;
  std::vector<std::string> fix, frames;
  std::string fixIds;
  bool fixOuterRing = false, replace = false;
  std::optional<double> spanLength;  // in --unit
  int spanInterfaces = 0;
  std::optional<double> overlapTolerance;
  ResolutionArguments resolution;
};

bool isMeshFile(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".obj" || ext == ".stl" || ext == ".ply";
}

// Files as given; folders give their OBJ, STL and PLY files in name order. Frame files are left out.
std::vector<std::string> partFiles(const std::vector<std::string>& given, const std::vector<std::string>& frames) {
  std::vector<std::string> files;
  const auto isFrame = [&](const fs::path& p) {
    return std::any_of(frames.begin(), frames.end(), [&](const std::string& f) { return fs::equivalent(f, p); });
  };
  for (const std::string& g : given) {
    if (!fs::exists(g)) throw InputError(g + ": no such file or folder");
    if (fs::is_directory(g)) {
      std::vector<std::string> inFolder;
      for (const auto& entry : fs::directory_iterator(g))
        if (entry.is_regular_file() && isMeshFile(entry.path()) && !isFrame(entry.path())) inFolder.push_back(entry.path().string());
      if (inFolder.empty()) throw InputError(g + ": holds no .obj, .stl or .ply file");
      std::sort(inFolder.begin(), inFolder.end());
      files.insert(files.end(), inFolder.begin(), inFolder.end());
    } else if (!isFrame(g)) {
      files.push_back(g);
    }
  }
  return files;
}

// "43,44,50-74": whole numbers and ranges, each once; refused whole on anything else.
std::vector<long> parseIdList(const std::string& text) {
  std::vector<long> ids;
  if (text.empty()) return ids;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    long from = -1, to = -1;
    char dash = 0, rest = 0;
    std::istringstream words(item);
    const bool range = item.find('-') != std::string::npos;
    const bool read = range ? static_cast<bool>(words >> from >> dash >> to) && dash == '-' : static_cast<bool>(words >> from);
    if (!read || (words >> rest) || from < 0 || (range && (to < from || to - from > 100000)))
      throw InputError("--fix-ids '" + text + "': '" + item + "' is not a part number or a range a-b; give e.g. 43,44,50-74");
    for (long id = from; id <= (range ? to : from); ++id) ids.push_back(id);
  }
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end())
    throw InputError("--fix-ids '" + text + "': a part number given twice");
  return ids;
}

void runAssemble(const AssembleArguments& a) {
  const auto start = std::chrono::steady_clock::now();
  checkBundleOutput(a.output, a.replace);
  const LengthUnit unit = parseLengthUnit(a.unit);
  AssembleOptions options;
  options.unit = a.unit;
  options.up = a.up;
  options.fixPatterns = a.fix;
  options.fixIds = parseIdList(a.fixIds);
  options.frameFiles = a.frames;
  options.fixOuterRing = a.fixOuterRing;
  if (a.spanLength && !(*a.spanLength > 0)) throw InputError("--span-length must be positive (in --unit)");
  if (a.spanInterfaces < 0) throw InputError("--span-interfaces must be a positive whole number");
  if (a.spanLength) options.spanLength = *a.spanLength * unit.metres;
  options.spanInterfaces = a.spanInterfaces;
  options.resolution = shapeResolution(a.resolution, unit.metres, "assemble");
  options.limits = shapeLimits(a.resolution);

  PrepLog log;
  log.now = [](const std::string& m) { std::cerr << "assemble: " << m << "\n"; };
  AssembleReport report;
  const Bundle bundle = assembleParts(partFiles(a.parts, a.frames), options, log, report);
  for (const auto& note : log.notes) std::cerr << "assemble: note: " << note << "\n";
  for (const auto& warning : log.warnings) std::cerr << "assemble: warning: " << warning << "\n";

  const AssemblySummary summary = checkAssemblyBeforeWriting(
      bundle, a.overlapTolerance ? std::optional<double>(*a.overlapTolerance * unit.metres) : std::nullopt, 0.0,
      "check that every part was exported once, in one unit, or raise --overlap-tolerance",
      "check the parts' unit (--unit) and up axis (--up), unless they were modelled with clearances", false);
  writeBundle(a.output, bundle);

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("assembly: %zu file(s), %zu piece(s); up axis %s turned to +z\n", report.files, report.pieces, a.up.c_str());
  for (const Shape& s : bundle.shapes) {
    const auto users = std::count_if(bundle.bodies.begin(), bundle.bodies.end(),
                                     [&](const Body& b) { return bundle.shapes[b.shape].name == s.name; });
    std::printf("  shape %-20s %2ld bod%s, %s\n", s.name.c_str(), static_cast<long>(users), users == 1 ? "y " : "ies",
                levelSetPath(s).c_str());
  }
  printAssemblySummary(bundle, summary, "assemble");
  printAssemblyVerdict(bundle, a.output);
  std::printf("  span rule     %s\n", report.spanRule.c_str());
  std::printf("written to %s in %.2f s\n", a.output.c_str(), seconds);
}

}  // namespace

void addAssembleCommand(CLI::App& app) {
  auto args = std::make_shared<AssembleArguments>();
  CLI::App* cmd = app.add_subcommand(
      "assemble", "Build a bundle from part meshes placed in world coordinates (an assembly exported by a design tool).");
  cmd->add_option("parts", args->parts, "Part meshes (OBJ, STL, PLY; each connected piece one body) or folders of them")
      ->required();
  cmd->add_option("--unit", args->unit, "Length unit of every file: m, cm, mm, um, in, ft")->required();
  cmd->add_option("--up", args->up, "The files' up axis (x, y or z), turned into +z")->capture_default_str();
  cmd->add_option("--fix", args->fix, "Fix the bodies whose name matches this glob pattern (repeatable), e.g. 'frame*'");
  cmd->add_option("--frame", args->frames, "A mesh of the fixed frame: each of its pieces is a fixed body (repeatable)");
  cmd->add_option("--fix-ids", args->fixIds,
                  "Fix the parts whose file names end in these numbers, e.g. TopoLite's Boundary_PartIDs: 43,44,50-74");
  cmd->add_flag("--fix-outer-ring", args->fixOuterRing, "Fix the bodies on the assembly's outer ring (in plan)");
  cmd->add_option("--span-length", args->spanLength, "L of k_n = E M / L, in --unit [default: estimated, docs/tiling.md]");
  cmd->add_option("--span-interfaces", args->spanInterfaces, "M of k_n = E M / L [default: estimated]");
  addResolutionOptions(*cmd, args->resolution);
  cmd->add_option("--overlap-tolerance", args->overlapTolerance,
                  "Initial overlap accepted between bodies, in --unit [default: 0.1 voxel]");
  cmd->add_option("-o,--output", args->output, "Bundle directory to write")->required();
  cmd->add_flag("--replace", args->replace, "Replace a bundle already in the output directory");
  cmd->footer("Example: tessera assemble parts/ --frame frame.obj --unit m --up y -o out/dome\n"
              "Identical parts share one shape; the same checks as tile (overlaps, contacts, interlocking).");
  cmd->callback([args] { runAssemble(*args); });
}

}  // namespace tessera::tools

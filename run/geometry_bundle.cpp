#include "run/geometry_bundle.h"

#include "geometry/base_surface.h"
#include "geometry/block_generators.h"
#include "geometry/plane_tiling.h"
#include "io/file_digest.h"
#include "io/folder_lock.h"
#include "io/input_error.h"
#include "levelset/assembly_checks.h"
#include "levelset/generated_slab.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// The recipe as text, every value exact, and the contents of its tiling or surface file (an
// edited file is another recipe): equal texts, equal bundles.
std::string recipeText(const GeometryRecipe& g) {
  std::ostringstream out;
  out.precision(17);
  out << "tiling " << g.tiling << "\npitch " << g.pitch << "\ngrid " << g.columns << " " << g.rows << "\nthickness " << g.thickness
      << "\nangle " << g.angle << "\nsurface " << g.surface << "\nradius " << g.radius << "\nfix " << g.fixPerimeter << "\nseed "
      << g.seed << "\nfamily " << g.family << "\nsize " << g.size << "\namplitude " << g.amplitude << "\nup " << g.up << "\n";
  if (g.family.empty() && !isTilingKind(g.tiling)) out << "tiling file " << fileDigest(g.tiling) << "\n";
  if (g.family.empty() && !isSurfaceKind(g.surface)) out << "surface file " << fileDigest(g.surface) << "\n";
  return out.str();
}

// A family block (tessera block) on the square grid, `size` apart, as parts in place.
std::vector<AssemblyPart> familySlabParts(const GeometryRecipe& g) {
  const double theta = g.angle * M_PI / 180, amplitude = g.amplitude > 0 ? g.amplitude : kDefaultAmplitudePerSize * g.size;
  TriangleMesh block;
  if (g.family == "planar") block = makePlanarBlock(g.size, g.thickness, theta);
  else if (g.family == "wave") block = makeWaveBlock(g.size, g.thickness, theta, amplitude, 1, 24);
  else if (g.family == "box") block = makeBox(g.size, g.size, g.thickness);
  else block = makeOsteomorphicBlock(g.size, g.size, g.thickness, amplitude, 0, 12);
  SquareGridOptions grid;
  grid.columns = g.columns;
  grid.rows = g.rows;
  grid.pitch = g.size;
  grid.alternate = g.family != "osteomorphic";  // osteomorphic copies match in the same orientation
  grid.fixPerimeter = g.fixPerimeter;
  std::vector<AssemblyPart> parts;
  for (const Placement& p : squareGrid(grid, g.family)) {
    AssemblyPart part{p.name, g.family + " block " + p.name, block, p.fixed};
    for (Eigen::Vector3d& x : part.mesh.vertices) x = p.rotation * x + p.translation;
    parts.push_back(std::move(part));
  }
  return parts;
}

}  // namespace

std::string geometryCache(const std::string& output) {
  // A case's run writes to SWEEP/case_N (or a folder inside it).
  const fs::path parent = fs::absolute(output).lexically_normal().parent_path();
  for (const fs::path& folder : {parent, parent.parent_path()})
    if (fs::exists(folder / "sweep.json")) return (folder / "bundles").string();
  return output;
}

std::string geometryBundle(const GeometryRecipe& recipe, const std::string& cache, const std::function<void(const std::string&)>& log) {
  if (cache.empty()) throw InputError("a scene with [geometry] needs an output folder, where its bundle is kept");
  const std::string text = recipeText(recipe);
  const fs::path folder = fs::path(cache) / ("geometry_" + textDigest(text).substr(0, 16));
  fs::create_directories(cache);
  const FileLock lock(folder.string() + ".lock");
  if (fs::exists(folder / "bundle.h5")) return folder.string();
  if (log) log("generating the [geometry] slab (" + (recipe.family.empty() ? recipe.tiling : recipe.family + " blocks") + ") into " + folder.string());
  PrepLog prep;
  AssembleReport report;
  Bundle bundle;
  if (!recipe.family.empty()) {
    AssembleOptions assemble;
    assemble.unit = "m";
    assemble.sameShapeTolerance = 1e-9;
    bundle = assembleParts(familySlabParts(recipe), assemble, prep, report);
  } else {
    GeneratedSlabOptions options;
    if (isTilingKind(recipe.tiling))
      options.tiling = {recipe.tiling, recipe.pitch, recipe.columns, recipe.rows, static_cast<unsigned>(recipe.seed)};
    else
      options.tilingFile = recipe.tiling;
    options.up = recipe.up;
    options.thickness = recipe.thickness;
    options.angle = recipe.angle * M_PI / 180;
    options.surface = baseSurface(recipe.surface, recipe.radius, 1.0, recipe.up);
    options.fixPerimeter = recipe.fixPerimeter;
    bundle = generatedSlab(options, "m", ShapeResolution{}, ShapeLimits{}, prep, report);
  }
  checkAssemblyBeforeWriting(bundle, std::nullopt, 0, "check geometry.pitch and geometry.angle", "check geometry.pitch and the unit (m)", true);
  checkBundleOutput(folder.string(), true);
  writeBundle(folder.string(), bundle);
  return folder.string();
}

}  // namespace tessera

// The scene-file parser: fills the plain settings structs, refuses anything it does not know.
#include "run/scene.h"

#include "io/input_error.h"
#include "io/text_file.h"
#include "geometry/base_surface.h"
#include "geometry/plane_tiling.h"
#include "levelset/shape.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// One table of the scene: each key read once, with its range; leftovers are unknown keys.
class Table {
public:
  Table(const std::string& file, const std::string& name, const toml::table* table)
      : file_(file), name_(name), table_(table) {}

  void number(const std::string& key, double& value, double lo, double hi, const std::string& unit) {
    const toml::node* node = find(key);
    if (!node) return;
    const std::optional<double> v = node->value<double>();
    if (!v) fail(key, "must be a number" + suffix(unit));
    if (!std::isfinite(*v)) fail(key, "must be a finite number" + suffix(unit) + ", got " + (std::isnan(*v) ? "nan" : "inf"));
    if (*v < lo || *v > hi) {
      std::ostringstream range;
      range << "must be in [" << lo << ", " << hi << "]" << suffix(unit) << ", got " << *v;
      fail(key, range.str());
    }
    value = *v;
  }

  void integer(const std::string& key, int& value, int lo, int hi) {
    const toml::node* node = find(key);
    if (!node) return;
    const std::optional<std::int64_t> v = node->value<std::int64_t>();
    if (!v || !node->is_integer() || *v < lo || *v > hi)
      fail(key, "must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    value = static_cast<int>(*v);
  }

  void boolean(const std::string& key, bool& value) {
    const toml::node* node = find(key);
    if (!node) return;
    if (!node->is_boolean()) fail(key, "must be true or false");
    value = *node->value<bool>();
  }

  void text(const std::string& key, std::string& value) {
    const toml::node* node = find(key);
    if (!node) return;
    if (!node->is_string()) fail(key, "must be a string");
    value = *node->value<std::string>();
  }

  template <int N>
  bool vector(const std::string& key, Eigen::Matrix<double, N, 1>& value, const std::string& unit) {
    const toml::node* node = find(key);
    if (!node) return false;
    const std::string what = "must be an array of " + std::to_string(N) + " numbers" + suffix(unit);
    const toml::array* a = node->as_array();
    if (!a || a->size() != N) fail(key, what);
    for (int k = 0; k < N; ++k) {
      const std::optional<double> v = (*a)[k].value<double>();
      if (!v || !std::isfinite(*v)) fail(key, what + (v ? " (finite)" : ""));
      value[k] = *v;
    }
    return true;
  }

  /// Every key of the table must have been read.
  void finish() const {
    if (!table_) return;
    for (const auto& [key, node] : *table_)
      if (!read_.count(std::string(key.str())))
        throw InputError(file_ + ": unknown key '" + where(std::string(key.str())) +
                         "'; see docs/scene.md for the keys of [" + name_ + "]");
  }

private:
  const toml::node* find(const std::string& key) {
    read_[key] = true;
    return table_ ? table_->get(key) : nullptr;
  }
  std::string where(const std::string& key) const { return name_.empty() ? key : name_ + "." + key; }
  static std::string suffix(const std::string& unit) { return unit.empty() ? "" : " (" + unit + ")"; }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(file_ + ": " + where(key) + " " + problem);
  }

  std::string file_, name_;
  const toml::table* table_;
  std::map<std::string, bool> read_;
};

}  // namespace

std::string readSceneFile(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError(path + ": no such scene file; see assets/scenes/default.toml for an example");
  return readTextFile(path);
}

Scene readScene(const std::string& path) { return readSceneText(readSceneFile(path), path); }

namespace {

// [material]: Young's modulus, density, friction, the tangential stiffness
void readMaterialTable(const std::string& path, const toml::table& root, Scene& scene) {
  Table material(path, "material", root["material"].as_table());
  material.number("youngs_modulus", scene.contact.youngsModulus, 1e3, 1e13, "Pa");
  material.number("density", scene.solver.density, 1e-3, 1e5, "kg/m^3");
  material.number("friction", scene.contact.friction, 0, 1e3, "Coulomb coefficient");
  material.number("tangential_ratio", scene.contact.tangentialRatio, 0, 100, "k_t / k_n");
  material.number("tangential_stiffness", scene.contact.tangentialStiffnessAbsolute, 0, 1e20,
                  "N/m^3; 0 = tangential_ratio x k_n");
  material.number("normal_viscosity", scene.contact.normalViscosity, 0, 1e12, "Pa s / m");
  std::string rule = stiffnessRuleName(scene.contact.stiffnessRule);
  material.text("stiffness_rule", rule);
  bool known = false;
  for (StiffnessRule r : {StiffnessRule::Span, StiffnessRule::Bars, StiffnessRule::Sections})
    if (rule == stiffnessRuleName(r)) scene.contact.stiffnessRule = r, known = true;
  if (!known)
    throw InputError(path + ": material.stiffness_rule must be \"span\", \"bars\" or \"sections\", got \"" + rule + "\"");
  if (scene.contact.tangentialStiffnessAbsolute > 0 && root["material"]["tangential_ratio"])
    throw InputError(path + ": give material.tangential_stiffness (N/m^3) or material.tangential_ratio (k_t / k_n), not both");
  material.finish();
}

// [span]: k_n's free span and interfaces (the bundle's unless given)
void readSpanTable(const std::string& path, const toml::table& root, Scene& scene) {
  scene.contact.spanLength = 0;  // from the bundle unless given
  scene.contact.spanInterfaces = 0;
  Table span(path, "span", root["span"].as_table());
  span.number("length", scene.contact.spanLength, 1e-6, 1e3, "m");
  span.integer("interfaces", scene.contact.spanInterfaces, 1, 100000);
  span.finish();
}

// [indenter]: the sphere, its speed and where it loads
void readIndenterTable(const std::string& path, const toml::table& root, Scene& scene) {
  Table indenter(path, "indenter", root["indenter"].as_table());
  indenter.number("radius", scene.indenter.radius, 0, 10, "m; 0 = radius_ratio x the loaded block's thickness");
  indenter.number("radius_ratio", scene.indenter.radiusRatio, 1e-3, 100, "of the loaded block's thickness");
  indenter.number("speed", scene.indenter.speed, 0, 100, "m/s; 0 = speed_ratio x sqrt(E / density) x (h / L)^2");
  indenter.number("speed_ratio", scene.indenter.speedRatio, 1e-9, 1, "of sqrt(E / density) x (h / L)^2");
  indenter.text("target", scene.indenter.target);
  indenter.vector<2>("offset", scene.indenter.offset, "m, in plan from the target's centroid");
  scene.indenter.atPoint = indenter.vector<2>("point", scene.indenter.point, "m, x and y on the slab's upper surface");
  if (scene.indenter.atPoint && (!scene.indenter.target.empty() || root["indenter"]["offset"]))
    throw InputError(path + ": give indenter.point (x, y) or indenter.target with indenter.offset, not both");
  indenter.number("clearance", scene.indenter.clearance, 0, 1, "m");
  indenter.number("stiffness_factor", scene.indenter.stiffnessFactor, 1e-3, 10, "x the blocks' k_n and k_t");
  indenter.finish();
}

// [protocol]: settling, delta_max, failure and the quasi-static checks
void readProtocolTable(const std::string& path, const toml::table& root, Scene& scene) {
  Table protocol(path, "protocol", root["protocol"].as_table());
  protocol.number("settle_kinetic", scene.protocol.settleKinetic, 0, 1e6, "J; 0 = settle_kinetic_ratio x sum m g h");
  protocol.number("settle_kinetic_ratio", scene.protocol.settleKineticRatio, 1e-15, 1, "of the free bodies' sum m g h");
  protocol.number("settle_max_time", scene.protocol.settleMaxTime, 0, 1e3, "s; 0 = settle_max_time_ratio x L^2 / (c t)");
  protocol.number("settle_max_time_ratio", scene.protocol.settleMaxTimeRatio, 1e-3, 1e6, "of L^2 / (c t)");
  protocol.number("delta_max", scene.protocol.deltaMax, 0, 10, "m; 0 = delta_max_ratio x the loaded block's thickness");
  protocol.number("delta_max_ratio", scene.protocol.deltaMaxRatio, 1e-3, 100, "of the loaded block's thickness");
  protocol.number("failure_load_fraction", scene.protocol.failureLoadFraction, 1e-3, 0.99, "of P_max");
  protocol.boolean("stop_on_failure", scene.protocol.stopOnFailure);
  protocol.number("quiet_travel", scene.protocol.quietTravel, 0, 100, "of the loaded block's thickness");
  protocol.number("rest_speed_ratio", scene.protocol.restSpeedRatio, 0, 1, "of the indenter's speed");
  protocol.number("fallen_clearance", scene.protocol.fallenClearance, 1e-3, 10, "of each body's size");
  protocol.number("stiffness_fit_ratio", scene.protocol.stiffnessFitRatio, 1e-3, 10, "of the loaded block's thickness");
  protocol.number("quasi_static_limit", scene.protocol.quasiStaticLimit, 1e-9, 1, "kinetic energy / indenter work");
  protocol.number("quasi_static_target", scene.protocol.quasiStaticTarget, 0, 1,
                  "kinetic energy / indenter work to keep the loading under; 0 = constant speed");
  if (root["protocol"]["fallen_distance"])
    throw InputError(path + ": protocol.fallen_distance is gone: a body now falls when no block contact holds it "
                            "(docs/physics.md, \"Failure\"); remove the key, or tune protocol.fallen_clearance (a ratio)");
  protocol.finish();
}

// [damping]
void readDampingTable(const std::string& path, const toml::table& root, Scene& scene) {
  Table damping(path, "damping", root["damping"].as_table());
  damping.number("local", scene.solver.localDamping, 0, 0.99, "fraction");
  damping.number("viscous", scene.solver.viscousDamping, 0, 1e9, "1/s");
  damping.finish();
}

// [solver]: time step, threads, gravity, level sets, method and contact evaluation
void readSolverTable(const std::string& path, const toml::table& root, Scene& scene) {
  Table solver(path, "solver", root["solver"].as_table());
  solver.number("time_step", scene.solver.timeStep, 0, 1, "s; 0 = automatic");
  solver.number("time_step_factor", scene.solver.timeStepFactor, 1e-4, 1, "of the stability limit");
  solver.integer("threads", scene.solver.threads, 0, kMaxThreads);
  solver.vector<3>("gravity", scene.solver.gravity, "m/s^2");
  if (!(scene.solver.gravity.norm() <= 1000))  // 100 g; also NaN
    throw InputError(path + ": solver.gravity must be at most 1000 m/s^2 (100 g) in size, e.g. [0, 0, -9.81]; 0 turns it off");
  solver.number("max_penetration", scene.solver.maxPenetration, 0, 1, "m; 0 = a quarter of the thinnest block");
  solver.number("broad_phase_margin", scene.solver.broadPhaseMargin, 0, 1, "m; 0 = 0.0063 x the thinnest block");
  solver.boolean("exact_convex_level_sets", scene.solver.exactConvexLevelSets);
  solver.boolean("exact_mesh_level_sets", scene.solver.exactMeshLevelSets);
  std::string method = scene.solver.method == SolverMethod::Implicit ? "implicit" : "explicit";
  solver.text("method", method);
  if (method != "explicit" && method != "implicit")
    throw InputError(path + ": solver.method must be \"explicit\" or \"implicit\", got \"" + method + "\"");
  scene.solver.method = method == "implicit" ? SolverMethod::Implicit : SolverMethod::Explicit;
  std::string evaluation = scene.contact.evaluation == ContactEvaluation::OneWay ? "one-way" : "two-way";
  solver.text("contact_evaluation", evaluation);
  if (evaluation != "two-way" && evaluation != "one-way")
    throw InputError(path + ": solver.contact_evaluation must be \"two-way\" or \"one-way\", got \"" + evaluation + "\"");
  scene.contact.evaluation = evaluation == "one-way" ? ContactEvaluation::OneWay : ContactEvaluation::TwoWay;
  std::string area = scene.contact.area == ContactArea::Nearest ? "nearest" : "blended";
  solver.text("contact_area", area);
  if (area != "blended" && area != "nearest")
    throw InputError(path + ": solver.contact_area must be \"blended\" or \"nearest\", got \"" + area + "\"");
  scene.contact.area = area == "nearest" ? ContactArea::Nearest : ContactArea::Blended;
  ImplicitSettings& implicit = scene.solver.implicit;
  solver.number("implicit_tolerance", implicit.tolerance, 1e-14, 1e-2, "of the force scale");
  solver.integer("implicit_max_iterations", implicit.maxIterations, 1, 1000);
  solver.number("implicit_max_increment", implicit.maxIncrement, 0, 1e3, "s; 0 = 1e4 explicit automatic steps");
  solver.number("implicit_max_travel", implicit.maxTravel, 0, 1, "m; 0 = implicit_max_travel_ratio x the thinnest block");
  solver.number("implicit_max_travel_ratio", implicit.maxTravelRatio, 1e-6, 1, "of the thinnest block");
  solver.number("implicit_max_travel_growth", implicit.maxTravelGrowth, 1, 1e3, "x implicit_max_travel");
  solver.number("implicit_smooth_reaction_change", implicit.smoothReactionChange, 1e-6, 0.2, "of the reaction per increment");
  solver.number("implicit_dynamic_increment_ratio", implicit.dynamicIncrementRatio, 1, 1e6, "x the explicit automatic step");
  solver.finish();
}

// [resolution]: node spacing and voxel over the bundle's
void readResolutionTable(const std::string& path, const toml::table& root, Scene& scene) {
  Table resolution(path, "resolution", root["resolution"].as_table());
  resolution.number("node_spacing", scene.resolution.nodeSpacing, 0, 1, "m; 0 = the bundle's");
  resolution.number("voxel", scene.resolution.voxelSize, 0, 1, "m; 0 = the bundle's");
  resolution.number("node_spacing_ratio", scene.resolution.nodeSpacingRatio, 0, 10,
                    "of each shape's thinnest extent; 0 = the bundle's");
  resolution.number("voxel_ratio", scene.resolution.voxelRatio, 0, 10, "of each shape's thinnest extent; 0 = the bundle's");
  resolution.number("edge_spacing_fraction", scene.resolution.edgeSpacingFraction, 0, 1,
                    "node spacing at sharp edges as a fraction of the node spacing; 1 = uniform; 0 = the bundle's");
  resolution.number("size_gradient", scene.resolution.sizeGradient, 0, 100,
                    "growth of the node spacing per unit distance from a sharp edge; 0 = the bundle's");
  if (scene.resolution.edgeSpacingFraction != 0 && !validEdgeSpacingFraction(scene.resolution.edgeSpacingFraction))
    throw InputError(path + ": resolution.edge_spacing_fraction must be 0 (the bundle's) or between 0.05 and 1, got " +
                     std::to_string(scene.resolution.edgeSpacingFraction) + "; 1 gives uniform nodes");
  if (scene.resolution.sizeGradient != 0 && !validSizeGradient(scene.resolution.sizeGradient))
    throw InputError(path + ": resolution.size_gradient must be 0 (the bundle's) or between 0.05 and 100, got " +
                     std::to_string(scene.resolution.sizeGradient));
  resolution.finish();
}

// [output]: sampling, snapshots, progress and checkpoints
void readOutputTable(const std::string& path, const toml::table& root, Scene& scene) {
  Table output(path, "output", root["output"].as_table());
  output.number("sample_every", scene.output.sampleEvery, 1e-9, 1, "m of travel");
  output.number("snapshot_every", scene.output.snapshotEvery, 1e-9, 1, "m of travel");
  output.number("progress_seconds", scene.output.progressSeconds, 0, 1e6, "s");
  output.number("checkpoint_seconds", scene.output.checkpointSeconds, 0, 1e6, "s");
  output.finish();
}

// The [geometry] keys whose values name files (a tiling, a surface), by key: the recipe's own
// strings, which a scene resolves beside itself.
std::vector<std::pair<std::string, std::string*>> recipeFiles(GeometryRecipe& g) {
  std::vector<std::pair<std::string, std::string*>> files;
  if (!isTilingKind(g.tiling)) files.emplace_back("tiling", &g.tiling);
  if (!isSurfaceKind(g.surface)) files.emplace_back("surface", &g.surface);
  return files;
}

// [geometry]: a slab generated from a tiling, in place of `bundle`
void readGeometryTable(const std::string& path, const toml::table& root, Scene& scene) {
  const toml::table* table = root["geometry"].as_table();
  if (!table) return;
  GeometryRecipe g;
  Table geometry(path, "geometry", table);
  geometry.text("tiling", g.tiling);
  geometry.number("pitch", g.pitch, 1e-6, 100, "m");
  Eigen::Vector2d grid(g.columns, g.rows);
  if (geometry.vector<2>("grid", grid, "columns, rows")) {
    if (grid.x() != std::round(grid.x()) || grid.y() != std::round(grid.y()) || grid.minCoeff() < 1 || grid.prod() > 10000)
      throw InputError(path + ": geometry.grid must be [columns, rows], whole numbers of at least 1 and 10000 tiles in all");
    g.columns = static_cast<int>(grid.x());
    g.rows = static_cast<int>(grid.y());
  }
  geometry.integer("columns", g.columns, 1, 10000);
  geometry.integer("rows", g.rows, 1, 10000);
  geometry.number("thickness", g.thickness, 1e-6, 100, "m");
  geometry.number("angle", g.angle, 0, 89.9, "degrees");
  geometry.text("surface", g.surface);
  geometry.text("up", g.up);
  if (g.up != "x" && g.up != "y" && g.up != "z") throw InputError(path + ": geometry.up must be \"x\", \"y\" or \"z\", got \"" + g.up + "\"");
  geometry.number("radius", g.radius, 0, 1e6, "m");
  std::string fix = "perimeter";
  geometry.text("fix", fix);
  if (fix != "perimeter" && fix != "none") throw InputError(path + ": geometry.fix must be \"perimeter\" or \"none\", got \"" + fix + "\"");
  g.fixPerimeter = fix == "perimeter";
  geometry.integer("seed", g.seed, 0, 1 << 30);
  geometry.text("family", g.family);
  geometry.number("size", g.size, 1e-6, 100, "m");
  geometry.number("amplitude", g.amplitude, 0, 100, "m");
  geometry.finish();
  const std::set<std::string> families{"", "planar", "wave", "box", "osteomorphic"};
  if (!families.count(g.family))
    throw InputError(path + ": geometry.family must be planar, wave, box or osteomorphic (or left out for a tiling), got \"" + g.family + "\"");
  for (const auto& [key, file] : recipeFiles(g))  // beside the scene
    if (fs::path(*file).is_relative()) *file = (fs::path(path).parent_path() / *file).string();
  scene.geometry = g;
}

}  // namespace

Scene readSceneText(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << e.source().begin;
    throw InputError(path + ": not valid TOML (" + std::string(e.description()) + " at " + where.str() + ")");
  }
  Scene scene;
  scene.path = path;
  const std::set<std::string> sections{"material", "span", "indenter", "protocol", "damping", "solver", "output",
                                       "resolution", "geometry"};
  for (const auto& [key, node] : root)
    if (!node.is_table() && std::string(key.str()) != "bundle")
      throw InputError(path + ": unknown key '" + std::string(key.str()) + "'; top-level keys: bundle and the tables [" +
                       "material], [span], [indenter], [protocol], [damping], [solver], [output], [resolution], [geometry]");
    else if (node.is_table() && !sections.count(std::string(key.str())))
      throw InputError(path + ": unknown table [" + std::string(key.str()) + "]; see docs/scene.md");

  Table top(path, "", &root);
  top.text("bundle", scene.bundle);
  readGeometryTable(path, root, scene);
  if (scene.bundle.empty() == !scene.geometry)
    throw InputError(path + (scene.bundle.empty() ? ": bundle = \"...\" is missing: the slab to load (a bundle directory), or a [geometry] to generate"
                                                  : ": give either bundle = \"...\" or a [geometry] table, not both"));
  if (!scene.bundle.empty() && fs::path(scene.bundle).is_relative()) scene.bundle = (fs::path(path).parent_path() / scene.bundle).string();

  readMaterialTable(path, root, scene);
  readSpanTable(path, root, scene);
  readIndenterTable(path, root, scene);
  readProtocolTable(path, root, scene);
  readDampingTable(path, root, scene);
  readSolverTable(path, root, scene);
  readResolutionTable(path, root, scene);
  readOutputTable(path, root, scene);
  return scene;
}

std::string sceneWithOverrides(const std::string& path, const std::vector<std::pair<std::string, double>>& overrides) {
  const Scene base = readScene(path);  // the base scene must be valid
  toml::table root = toml::parse_file(path);
  const std::string bundle = root["bundle"].value_or(std::string());
  if (!bundle.empty() && fs::path(bundle).is_relative())
    root.insert_or_assign("bundle", fs::absolute(fs::path(path).parent_path() / bundle).lexically_normal().string());
  if (base.geometry) {  // its files, absolute
    GeometryRecipe recipe = *base.geometry;
    for (const auto& [key, file] : recipeFiles(recipe))
      if (toml::table* g = root["geometry"].as_table(); g && g->contains(key))
        g->insert_or_assign(key, fs::absolute(*file).lexically_normal().string());
  }
  for (const auto& [key, value] : overrides) {
    const auto dot = key.find('.');
    if (dot == std::string::npos) throw InputError("scene key '" + key + "': give it as table.key, e.g. material.friction");
    const std::string table = key.substr(0, dot), name = key.substr(dot + 1);
    if (!root.contains(table)) root.insert(table, toml::table{});
    toml::table* t = root[table].as_table();
    if (!t) throw InputError("scene key '" + key + "': [" + table + "] is not a table of the scene");
    if (key == "span.interfaces" || key == "solver.threads" || key == "solver.implicit_max_iterations" || key == "geometry.columns" ||
        key == "geometry.rows" || key == "geometry.seed") {  // Table::integer
      if (!(std::isfinite(value) && value == std::round(value) && std::abs(value) < 1e15)) {
        std::ostringstream m;
        m << "scene key '" << key << "' takes a whole number, not " << value << " (its run would not be the value it is labelled)";
        throw InputError(m.str());
      }
      t->insert_or_assign(name, static_cast<std::int64_t>(value));
    } else {
      t->insert_or_assign(name, value);
    }
    // k_t is given one way or the other: the swept one replaces the scene's.
    if (key == "material.tangential_stiffness") t->erase("tangential_ratio");
    if (key == "material.tangential_ratio") t->erase("tangential_stiffness");
  }
  std::ostringstream out;
  out << root << "\n";
  return out.str();
}

}  // namespace tessera

// tessera inspect: what a bundle holds, and the signed distance of a shape at a point.
#include "io/input_error.h"
#include "io/json_text.h"
#include "geometry/length_unit.h"
#include "geometry/mesh_features.h"
#include "geometry/point_spacing.h"
#include "geometry/surface_nodes.h"
#include "levelset/bundle.h"
#include "tools/commands.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <numeric>
#include <sstream>

namespace tessera::tools {

namespace {

struct InspectArguments {
  std::string bundle;
  bool json = false;
  std::string shape;
  std::string point;        // "X,Y,Z" in --unit
  std::string unit = "mm";  // for --sdf input and text output
};

nlohmann::json toJson(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json toJson(const Eigen::Matrix3d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) rows.push_back({m(i, 0), m(i, 1), m(i, 2)});
  return rows;
}

nlohmann::json describeShape(const Shape& s) {
  const SpacingStats spacing = spacingStats(s.nodes.positions, s.nodes.patches);
  // The block's symmetries, and how many of them its nodes keep (bundles prepared before nodes kept
  // them keep none but the identity; docs/geometry.md, "Surface nodes").
  const double size = boundingBox(s.mesh.vertices).diagonal().norm();
  const SymmetryGroup symmetry = findSymmetries(s.mesh, findFeatures(s.mesh, s.resolution.featureAngle), 1e-6 * size);
  const double areaSum = std::accumulate(s.nodes.areas.begin(), s.nodes.areas.end(), 0.0);
  return {
      {"name", s.name},
      {"source_file", s.source.file},
      {"source_unit", s.source.unit},
      {"volume_m3", s.mass.volume},
      {"surface_area_m2", s.mass.surfaceArea},
      {"centroid_m", toJson(s.mass.centroid)},
      {"inertia_per_density_m5", toJson(s.mass.inertia)},
      {"principal_moments_per_density_m5", toJson(s.mass.principalMoments)},
      {"principal_axes", toJson(s.mass.principalAxes)},
      {"mesh", {{"vertices", s.mesh.vertices.size()}, {"triangles", s.mesh.triangles.size()}}},
      {"nodes",
       {{"count", s.nodes.size()},
        {"area_sum_m2", areaSum},
        {"requested_spacing_m", s.resolution.nodeSpacing},
        {"edge_spacing_fraction", s.resolution.edgeSpacingFraction},
        {"size_gradient", s.resolution.sizeGradient},
        {"nearest_spacing_m", {{"min", spacing.min}, {"mean", spacing.mean}, {"max", spacing.max}}},
        {"symmetries_kept", keptSymmetries(s.nodes, symmetry, 1e-9 * size)}}},
      {"symmetries", symmetry.size()},
      {"sdf",
       {{"voxel_size_m", s.sdf.voxelSize},
        {"dims", {s.sdf.dims[0], s.sdf.dims[1], s.sdf.dims[2]}},
        {"origin_m", toJson(s.sdf.origin)},
        {"exterior_band_voxels", s.resolution.exteriorBandVoxels},
        {"vdb_file", s.name + ".vdb"}}},
      {"level_set", levelSetPath(s)},
      {"convex_deviation_m", s.convex ? nlohmann::json(s.convex->deviation) : nlohmann::json(nullptr)},
  };
}

nlohmann::json describeBodies(const Bundle& b) {
  nlohmann::json bodies = nlohmann::json::array();
  for (const Body& body : b.bodies)
    bodies.push_back({{"name", body.name},
                      {"shape", b.shapes[body.shape].name},
                      {"position_m", toJson(body.position)},
                      {"orientation_wxyz", {body.orientation.w(), body.orientation.x(), body.orientation.y(), body.orientation.z()}},
                      {"fixed", body.fixed}});
  return bodies;
}

void printShapeText(const nlohmann::json& j, double unit, const std::string& unitName) {
  const auto len = [&](double metres) { return metres / unit; };
  const auto vec = [&](const nlohmann::json& v, double scale) {
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", v[0].get<double>() / scale, v[1].get<double>() / scale,
                  v[2].get<double>() / scale);
    return std::string(buffer);
  };
  const auto& n = j["nodes"];
  const auto& g = j["sdf"];
  std::printf("shape '%s'\n", j["name"].get<std::string>().c_str());
  std::printf("  source              %s (unit %s)\n", j["source_file"].get<std::string>().c_str(),
              j["source_unit"].get<std::string>().c_str());
  std::printf("  volume              %.9g %s^3\n", j["volume_m3"].get<double>() / (unit * unit * unit), unitName.c_str());
  std::printf("  surface area        %.9g %s^2\n", j["surface_area_m2"].get<double>() / (unit * unit), unitName.c_str());
  std::printf("  centroid            %s %s (source mesh frame)\n", vec(j["centroid_m"], unit).c_str(), unitName.c_str());
  std::printf("  principal inertia   %s %s^5 (per unit density; x density = mass moment)\n",
              vec(j["principal_moments_per_density_m5"], std::pow(unit, 5)).c_str(), unitName.c_str());
  std::printf("  nodes               %zu, area sum %.9g %s^2\n", n["count"].get<std::size_t>(),
              n["area_sum_m2"].get<double>() / (unit * unit), unitName.c_str());
  std::printf("  nearest-node gap    min %.4g / mean %.4g / max %.4g %s within a face (requested %.4g, %.4g at sharp "
              "edges, size gradient %.3g)\n",
              len(n["nearest_spacing_m"]["min"]), len(n["nearest_spacing_m"]["mean"]), len(n["nearest_spacing_m"]["max"]),
              unitName.c_str(), len(n["requested_spacing_m"]),
              len(n["requested_spacing_m"]) * n["edge_spacing_fraction"].get<double>(), n["size_gradient"].get<double>());
  const std::size_t symmetries = j["symmetries"], kept = n["symmetries_kept"];
  std::printf("  symmetries          %zu (mirrors and rotations of the block); the nodes keep %zu%s\n", symmetries, kept,
              kept < symmetries ? ": prepare the shape again (tessera prep, tile) for nodes that keep them all" : "");
  std::printf("  grid                %d x %d x %d, voxel %.4g %s, band %d voxels, file %s\n", g["dims"][0].get<int>(),
              g["dims"][1].get<int>(), g["dims"][2].get<int>(), len(g["voxel_size_m"]), unitName.c_str(),
              g["exterior_band_voxels"].get<int>(), g["vdb_file"].get<std::string>().c_str());
  std::printf("  level set           %s\n", j["level_set"].get<std::string>().c_str());
}

Eigen::Vector3d parsePoint(const std::string& text, double unit) {
  std::stringstream in(text);
  Eigen::Vector3d p;
  char comma = 0;
  if (!(in >> p.x() >> comma) || comma != ',' || !(in >> p.y() >> comma) || comma != ',' || !(in >> p.z()) ||
      !(in >> std::ws).eof())
    throw InputError("--sdf '" + text + "': give a point as X,Y,Z (e.g. --sdf 0,0,1.59)");
  return p * unit;
}

void runInspect(const InspectArguments& a) {
  const Bundle bundle = readBundle(a.bundle);
  const LengthUnit unit = parseLengthUnit(a.unit);

  if (!a.point.empty()) {
    if (a.shape.empty() && bundle.shapes.size() != 1)
      throw InputError(a.bundle + ": holds " + std::to_string(bundle.shapes.size()) + " shapes; name one with --shape");
    const int index = a.shape.empty() ? 0 : bundle.findShape(a.shape);
    if (index < 0) throw InputError(a.bundle + ": no shape named '" + a.shape + "'");
    const Shape& s = bundle.shapes[index];
    const Eigen::Vector3d x = parsePoint(a.point, unit.metres);
    const SdfSample sample = s.sdf.sample(x);
    if (a.json) {
      std::cout << jsonText(nlohmann::json{{"shape", s.name},
                                           {"point_m", toJson(x)},
                                           {"inside_grid", s.sdf.contains(x)},
                                           {"phi_m", sample.phi},
                                           {"gradient", toJson(sample.gradient)}});
    } else {
      std::printf("shape '%s' at (%s) %s, body frame:\n", s.name.c_str(), a.point.c_str(), unit.name.c_str());
      std::printf("  signed distance  %.6g %s (%s)%s\n", sample.phi / unit.metres, unit.name.c_str(),
                  sample.phi < 0 ? "inside" : "outside", s.sdf.contains(x) ? "" : ", beyond the grid: a lower bound");
      std::printf("  gradient         (%.6g, %.6g, %.6g), |grad| = %.4f\n", sample.gradient.x(), sample.gradient.y(),
                  sample.gradient.z(), sample.gradient.norm());
    }
    return;
  }

  nlohmann::json shapes = nlohmann::json::array();
  for (const Shape& s : bundle.shapes)
    if (a.shape.empty() || s.name == a.shape) shapes.push_back(describeShape(s));
  if (!a.shape.empty() && shapes.empty()) throw InputError(a.bundle + ": no shape named '" + a.shape + "'");
  if (a.json) {
    std::cout << jsonText(nlohmann::json{{"bundle", a.bundle},
                                         {"format_version", kBundleFormatVersion},
                                         {"generator", bundle.generator},
                                         {"length_unit", "m"},
                                         {"shapes", shapes},
                                         {"bodies", describeBodies(bundle)},
                                         {"span", {{"length_m", bundle.spanLength}, {"interfaces", bundle.spanInterfaces}}}});
    return;
  }
  std::printf("bundle %s (format %d, written by %s): %zu shape(s), %zu bodies\n", a.bundle.c_str(), kBundleFormatVersion,
              bundle.generator.c_str(), bundle.shapes.size(), bundle.bodies.size());
  for (const auto& j : shapes) printShapeText(j, unit.metres, unit.name);
  if (!bundle.bodies.empty()) {
    int fixed = 0;
    for (const Body& b : bundle.bodies) fixed += b.fixed;
    std::printf("bodies: %zu (%d fixed, %zu free); --json lists each with its pose\n", bundle.bodies.size(), fixed,
                bundle.bodies.size() - fixed);
  }
  if (bundle.spanInterfaces > 0)
    std::printf("span: L = %.6g %s free span, M = %d interfaces across it\n", bundle.spanLength / unit.metres,
                unit.name.c_str(), bundle.spanInterfaces);
}

}  // namespace

void addInspectCommand(CLI::App& app) {
  auto args = std::make_shared<InspectArguments>();
  CLI::App* cmd = app.add_subcommand("inspect", "Print what a bundle holds, or a shape's signed distance at a point.");
  cmd->add_option("bundle", args->bundle, "Bundle directory (or its bundle.h5)")->required();
  cmd->add_flag("--json", args->json, "Print JSON (SI units) instead of text");
  cmd->add_option("--shape", args->shape, "Only this shape");
  cmd->add_option("--sdf", args->point, "Print the signed distance and gradient at body-frame point X,Y,Z (in --unit)");
  cmd->add_option("--unit", args->unit, "Length unit for --sdf and the text output: m, cm, mm, um, in, ft")
      ->capture_default_str();
  cmd->callback([args] { runInspect(*args); });
}

}  // namespace tessera::tools

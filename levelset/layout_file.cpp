#include "levelset/layout_file.h"
#include "io/json_text.h"

#include "io/input_error.h"
#include "geometry/length_unit.h"
#include "io/safe_write.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace tessera {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kLayoutFormat = "tessera-layout";
constexpr int kLayoutVersion = 1;

class Reader {
public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw InputError(path_ + ": " + where + ": " + problem);
  }

  void onlyKeys(const json& object, const std::set<std::string>& allowed, const std::string& where) const {
    if (!object.is_object()) fail(where, "must be a JSON object");
    for (const auto& item : object.items())
      if (!allowed.count(item.key())) {
        std::string list;
        for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
        fail(where, "unknown key '" + item.key() + "' (allowed: " + list + ")");
      }
  }

  double number(const json& value, const std::string& where) const {
    if (!value.is_number()) fail(where, "must be a number");
    const double v = value.get<double>();
    if (!std::isfinite(v)) fail(where, "must be finite");
    return v;
  }

  std::vector<double> numbers(const json& value, std::size_t count, const std::string& where) const {
    if (!value.is_array() || value.size() != count)
      fail(where, "must be an array of " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (const auto& v : value) {
      // JSON has no NaN; nlohmann reads "NaN" strings as strings: refuse them here.
      if (!v.is_number()) fail(where, "must hold numbers only (no NaN, no strings)");
      out.push_back(number(v, where));
    }
    return out;
  }

  std::string text(const json& value, const std::string& where) const {
    if (!value.is_string() || value.get<std::string>().empty()) fail(where, "must be a non-empty string");
    return value.get<std::string>();
  }

private:
  std::string path_;
};

}  // namespace

Layout readLayout(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the layout file; check the path");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::exception& e) {  // a syntax error, or a number too large for a double
    throw InputError(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  const Reader r(path);
  r.onlyKeys(root, {"format", "version", "unit", "shapes", "bodies", "span"}, "top level");
  if (!(root.contains("format") && root["format"] == kLayoutFormat))
    r.fail("format", std::string("must be \"") + kLayoutFormat + "\"");
  if (!(root.contains("version") && root["version"].is_number_integer() && root["version"] == kLayoutVersion))
    r.fail("version", "must be " + std::to_string(kLayoutVersion) + " (this tessera reads layout version 1)");

  Layout layout;
  if (!root.contains("unit")) r.fail("unit", "missing: state the unit of every length, e.g. \"unit\": \"mm\"");
  layout.unit = r.text(root["unit"], "unit");
  double scale = 0.0;
  try {
    scale = parseLengthUnit(layout.unit).metres;
  } catch (const InputError& e) {
    r.fail("unit", e.what());
  }
  const fs::path folder = fs::path(path).parent_path();
  const auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() ? p : (folder / p).string(); };

  if (!root.contains("shapes") || !root["shapes"].is_object() || root["shapes"].empty())
    r.fail("shapes", "missing or empty: name at least one shape, e.g. \"shapes\": {\"block\": {\"mesh\": \"block.obj\"}}");
  for (const auto& [key, value] : root["shapes"].items()) {
    const std::string where = "shape '" + key + "'";
    r.onlyKeys(value, {"mesh", "bundle", "shape", "voxel", "spacing"}, where);
    LayoutShape s;
    s.key = key;
    if (value.contains("mesh") == value.contains("bundle")) r.fail(where, "give exactly one of \"mesh\" or \"bundle\"");
    if (value.contains("mesh")) s.mesh = resolve(r.text(value["mesh"], where + " mesh"));
    if (value.contains("bundle")) {
      s.bundle = resolve(r.text(value["bundle"], where + " bundle"));
      s.bundleShape = value.contains("shape") ? r.text(value["shape"], where + " shape") : key;
    }
    if (value.contains("voxel")) s.voxel = r.number(value["voxel"], where + " voxel") * scale;
    if (value.contains("spacing")) s.spacing = r.number(value["spacing"], where + " spacing") * scale;
    layout.shapes.push_back(s);
  }

  if (!root.contains("bodies") || !root["bodies"].is_array() || root["bodies"].empty())
    r.fail("bodies", "missing or empty: list at least one body");
  std::set<std::string> names;
  int index = 0;
  for (const auto& value : root["bodies"]) {
    std::string where = "body " + std::to_string(index++);
    r.onlyKeys(value, {"name", "shape", "position", "quaternion", "rotate_z_deg", "fixed"}, where);
    Placement p;
    if (!value.contains("name")) r.fail(where, "missing \"name\"");
    p.name = r.text(value["name"], where + " name");
    where = "body '" + p.name + "'";
    if (!names.insert(p.name).second) r.fail(where, "duplicate name; every body needs its own");
    if (!value.contains("shape")) r.fail(where, "missing \"shape\"");
    p.shape = r.text(value["shape"], where + " shape");
    if (!root["shapes"].contains(p.shape)) r.fail(where, "unknown shape '" + p.shape + "'; define it under \"shapes\"");
    if (!value.contains("position")) r.fail(where, "missing \"position\" [x, y, z]");
    const auto x = r.numbers(value["position"], 3, where + " position");
    p.translation = Eigen::Vector3d(x[0], x[1], x[2]) * scale;
    if (value.contains("quaternion") && value.contains("rotate_z_deg"))
      r.fail(where, "give either \"quaternion\" or \"rotate_z_deg\", not both");
    if (value.contains("quaternion")) {
      const auto q = r.numbers(value["quaternion"], 4, where + " quaternion");
      p.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      const double norm = p.rotation.norm();
      if (std::abs(norm - 1.0) > 1e-6)
        r.fail(where, "quaternion [w, x, y, z] has norm " + std::to_string(norm) + ", not 1; normalise it");
      p.rotation.normalize();
    } else if (value.contains("rotate_z_deg")) {
      p.rotation = Eigen::AngleAxisd(r.number(value["rotate_z_deg"], where + " rotate_z_deg") * M_PI / 180,
                                     Eigen::Vector3d::UnitZ());
    }
    if (value.contains("fixed")) {
      if (!value["fixed"].is_boolean()) r.fail(where, "\"fixed\" must be true or false");
      p.fixed = value["fixed"].get<bool>();
    }
    layout.bodies.push_back(p);
  }

  if (root.contains("span")) {
    r.onlyKeys(root["span"], {"length", "interfaces"}, "span");
    if (!root["span"].contains("length") || !root["span"].contains("interfaces"))
      r.fail("span", "give both \"length\" (free span L) and \"interfaces\" (M)");
    layout.spanLength = r.number(root["span"]["length"], "span length") * scale;
    // (Compared as JSON numbers: get<int>() would wrap 4294967297 to 1.)
    if (!root["span"]["interfaces"].is_number_integer() || root["span"]["interfaces"] < 1 ||
        root["span"]["interfaces"] > 1000000)
      r.fail("span", "\"interfaces\" must be a whole number from 1 to 1000000");
    layout.spanInterfaces = root["span"]["interfaces"].get<int>();
    if (!(layout.spanLength > 0)) r.fail("span", "\"length\" must be positive");
  }
  return layout;
}

void writeLayout(const std::string& path, const Layout& layout) {
  const double scale = parseLengthUnit(layout.unit).metres;
  json root;
  root["format"] = kLayoutFormat;
  root["version"] = kLayoutVersion;
  root["unit"] = layout.unit;
  root["shapes"] = json::object();
  for (const LayoutShape& s : layout.shapes) {
    json shape;
    if (!s.mesh.empty()) shape["mesh"] = s.mesh;
    if (!s.bundle.empty()) {
      shape["bundle"] = s.bundle;
      shape["shape"] = s.bundleShape.empty() ? s.key : s.bundleShape;
    }
    if (s.voxel) shape["voxel"] = *s.voxel / scale;
    if (s.spacing) shape["spacing"] = *s.spacing / scale;
    root["shapes"][s.key] = shape;
  }
  root["bodies"] = json::array();
  for (const Placement& p : layout.bodies) {
    const Eigen::Vector3d x = p.translation / scale;
    root["bodies"].push_back({{"name", p.name},
                              {"shape", p.shape},
                              {"position", {x.x(), x.y(), x.z()}},
                              {"quaternion", {p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z()}},
                              {"fixed", p.fixed}});
  }
  if (layout.spanInterfaces > 0)
    root["span"] = {{"length", layout.spanLength / scale}, {"interfaces", layout.spanInterfaces}};
  writeTextFileSafely(fs::path(path), jsonText(root));
}

}  // namespace tessera

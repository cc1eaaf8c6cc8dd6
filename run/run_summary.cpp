#include "run/run_summary.h"

#include "io/input_error.h"
#include "io/text_file.h"
#include "run/curve_table.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace tessera {

namespace {

// From SI to a key's unit (the suffix of its name in summary.json).
double unitScale(const std::string& unit) {
  if (unit == "mm" || unit == "mJ" || unit == "mm_per_s") return 1e3;
  if (unit == "N_per_mm") return 1e-3;
  if (unit == "GPa") return 1e-9;
  return 1.0;  // N, J, s, N_per_m3, or none
}

// The two directions of serializeSummary's one list of fields. JsonOut writes each field under
// its name and unit ("delta_at_peak_mm", in mm), or its plain name in SI units; JsonIn reads it
// back from the file's keys, naming the key it misses.
struct JsonOut {
  static constexpr bool reading = false;
  nlohmann::json& j;
  bool units;
  std::string key(const char* name, const char* unit) const {
    return units && *unit ? std::string(name) + "_" + unit : std::string(name);
  }
  void number(const char* name, const char* unit, double& v) const { j[key(name, unit)] = v * (units ? unitScale(unit) : 1.0); }
  // A number that is null where it does not apply (no failure).
  void optionalNumber(const char* name, const char* unit, double& v, bool present) const {
    if (present) number(name, unit, v);
    else j[key(name, unit)] = nullptr;
  }
  void range(const char* name, const char* unit, double& from, double& to) const {
    const double s = units ? unitScale(unit) : 1.0;
    j[key(name, unit)] = {from * s, to * s};
  }
  bool optionalRange(const char* name, const char* unit, double& from, double& to) const {
    range(name, unit, from, to);
    return true;
  }
  void value(const char* name, std::string& v) const { j[name] = v; }
  void value(const char* name, long& v) const { j[name] = v; }
  void value(const char* name, bool& v) const { j[name] = v; }
  template <class F>
  void object(const char* name, F&& fields) const {
    nlohmann::json o = nlohmann::json::object();
    fields(JsonOut{o, units});
    j[name] = std::move(o);
  }
  template <class F>
  void optionalObject(const char* name, bool present, F&& fields) const {
    if (present) object(name, fields);
    else j[name] = nullptr;
  }
  template <class T, class F>
  void list(const char* name, std::vector<T>& items, F&& fields) const {
    nlohmann::json a = nlohmann::json::array();
    for (T& item : items) {
      nlohmann::json o = nlohmann::json::object();
      fields(JsonOut{o, units}, item);
      a.push_back(std::move(o));
    }
    j[name] = std::move(a);
  }
};

struct JsonIn {
  static constexpr bool reading = true;
  const nlohmann::json& j;
  std::string where;  // the keys above this object, for messages ("response.at_peak.")

  const nlohmann::json& at(const std::string& key, bool (nlohmann::json::*is)() const noexcept, const char* type) const {
    if (!j.contains(key)) throw InputError("summary.json: no '" + where + key + "' (cut short, or written by another version of Tessera); run the case again");
    const nlohmann::json& v = j[key];
    if (!(v.*is)()) throw InputError("summary.json: '" + where + key + "' is not " + type);
    return v;
  }
  static std::string key(const char* name, const char* unit) { return *unit ? std::string(name) + "_" + unit : std::string(name); }
  // A number, or null: JSON has no NaN or infinity, and a non-finite value is written as null
  // (P* without a span, say), read back as NaN.
  void number(const char* name, const char* unit, double& v) const {
    const nlohmann::json& x = at(key(name, unit), &nlohmann::json::is_primitive, "a number");
    if (x.is_null()) {
      v = std::nan("");
      return;
    }
    if (!x.is_number()) throw InputError("summary.json: '" + where + key(name, unit) + "' is not a number");
    v = x.get<double>() / unitScale(unit);
  }
  // Null where it does not apply: v keeps its default (a failure deflection of -1: none).
  void optionalNumber(const char* name, const char* unit, double& v, bool) const {
    if (!j.contains(key(name, unit)) || !j[key(name, unit)].is_null()) number(name, unit, v);
  }
  void range(const char* name, const char* unit, double& from, double& to) const {
    const nlohmann::json& a = at(key(name, unit), &nlohmann::json::is_array, "a list");
    if (a.size() != 2 || !a[0].is_number() || !a[1].is_number())
      throw InputError("summary.json: '" + where + key(name, unit) + "' is not a pair of numbers");
    from = a[0].get<double>() / unitScale(unit);
    to = a[1].get<double>() / unitScale(unit);
  }
  // A range a summary of an older version lacks: false (from and to left alone) where it is absent.
  bool optionalRange(const char* name, const char* unit, double& from, double& to) const {
    if (!j.contains(key(name, unit))) return false;
    range(name, unit, from, to);
    return true;
  }
  void value(const char* name, std::string& v) const { v = at(name, &nlohmann::json::is_string, "a string").get<std::string>(); }
  void value(const char* name, long& v) const { v = at(name, &nlohmann::json::is_number_integer, "a whole number").get<long>(); }
  void value(const char* name, bool& v) const { v = at(name, &nlohmann::json::is_boolean, "true or false").get<bool>(); }
  template <class F>
  void object(const char* name, F&& fields) const {
    fields(JsonIn{at(name, &nlohmann::json::is_object, "an object"), where + name + "."});
  }
  template <class F>
  void optionalObject(const char* name, bool, F&& fields) const {
    if (!j.contains(name) || !j[name].is_null()) object(name, fields);
  }
  template <class T, class F>
  void list(const char* name, std::vector<T>& items, F&& fields) const {
    const nlohmann::json& a = at(name, &nlohmann::json::is_array, "a list");
    items.clear();
    for (std::size_t k = 0; k < a.size(); ++k) {
      if (!a[k].is_object()) throw InputError("summary.json: '" + where + name + "' holds an entry that is not an object");
      fields(JsonIn{a[k], where + name + "[" + std::to_string(k) + "]."}, items.emplace_back());
    }
  }
};

template <class Io>
void serializeContactState(const Io& io, ContactState& c) {
  io.number("delta", "mm", c.delta);
  io.number("block_displacement", "mm", c.blockDisplacement);
  io.number("indenter_penetration", "mm", c.indenterPenetration);
  io.number("sliding_fraction", "", c.slidingFraction);
  io.number("loaded_sliding_fraction", "", c.loadedSlidingFraction);
  io.number("indenter_speed", "mm_per_s", c.indenterSpeed);
}

// "response": the response parameters, the failure and the energy balance at the end.
template <class Io>
void serializeResponse(const Io& io, RunSummary& s) {
  ResponseParameters& r = s.response;
  const bool failed = r.failureDeflection >= 0;  // (writing; a reader finds null)
  io.number("peak_load", "N", r.peakLoad);
  io.number("delta_at_peak", "mm", r.deltaAtPeak);
  // (Added 2026-11-27: an older summary has none, and reads back the peak's delta alone.)
  if (!io.optionalRange("peak_range", "mm", r.peakRangeFrom, r.peakRangeTo)) r.peakRangeFrom = r.peakRangeTo = r.deltaAtPeak;
  io.number("stiffness", "N_per_mm", r.stiffness);
  io.range("stiffness_fit_window", "mm", r.fitFrom, r.fitTo);
  io.optionalNumber("failure_deflection", "mm", r.failureDeflection, failed);
  io.number("failure_load_fraction", "", s.failureLoadFraction);
  io.optionalNumber("block_displacement_at_failure", "mm", r.atFailure.blockDisplacement, failed);
  io.number("loading_energy", "mJ", r.energy);
  io.number("loading_energy_to_end", "mJ", r.energyToEnd);
  io.number("ultimate_deflection", "mm", r.ultimateDeflection);
  io.value("failure_mode", r.failureMode);
  io.list("fallen", s.fallen, [](const auto& o, FallenBody& b) {
    o.value("name", b.name);
    o.number("delta", "mm", b.delta);
    o.value("retired", b.retired);
    o.value("touching", b.touching);
  });
  io.list("load_drops", r.drops, [](const auto& o, LoadDrop& d) {
    o.number("delta", "mm", d.delta);
    o.number("load_before", "N", d.before);
    o.number("load_after", "N", d.after);
  });
  io.object("at_peak", [&](const auto& o) { serializeContactState(o, r.atPeak); });
  io.optionalObject("at_failure", failed, [&](const auto& o) { serializeContactState(o, r.atFailure); });
  io.object("end", [&](const auto& o) {
    o.number("delta", "mm", r.end.delta);
    o.number("load", "N", r.end.load);
    o.number("block_displacement", "mm", r.end.blockDisplacement);
  });
  // The energy balance at the end: the curve's energy columns, by their names, in mJ.
  io.object("energy", [&](const auto& o) {
    for (const CurveColumn& c : curveColumns())
      if (std::string(c.unit) == "J") o.number(c.name, "mJ", r.end.*c.field);
  });
  io.number("quasi_static_ratio", "", r.quasiStaticRatio);
  io.value("quasi_static", r.quasiStatic);
  io.number("quasi_static_target", "", s.quasiStaticTarget);
  io.number("loading_speed_to_peak", "mm_per_s", r.loadingSpeed);
  io.number("peak_load_normalised", "", r.peakLoadNormalised);
  io.number("delta_at_peak_normalised", "", r.deltaAtPeakNormalised);
  io.number("thickness", "mm", r.thickness);
  io.number("delta_max", "mm", s.deltaMax);
}

template <class Io>
void serializeMaterial(const Io& io, SummaryMaterial& m) {
  io.number("youngs_modulus", "GPa", m.youngsModulus);
  io.number("friction", "", m.friction);
  io.number("normal_stiffness", "N_per_m3", m.normalStiffness);
  io.number("tangential_stiffness", "N_per_m3", m.tangentialStiffness);
  io.number("indenter_stiffness_factor", "", m.indenterStiffnessFactor);
  io.number("indenter_radius", "mm", m.indenterRadius);
  io.number("indenter_speed", "mm_per_s", m.indenterSpeed);
  io.number("span_length", "mm", m.spanLength);
  io.value("span_interfaces", m.spanInterfaces);
  io.value("contact_evaluation", m.contactEvaluation);
  io.value("contact_area", m.contactArea);
  io.value("stiffness_rule", m.stiffnessRule);
}

template <class Io>
void serializeRun(const Io& io, SummaryRun& r) {
  io.value("method", r.method);
  io.number("time_step", "s", r.timeStep);
  io.value("steps", r.steps);
  io.value("newton_iterations", r.newtonIterations);
  io.value("cutbacks", r.cutbacks);
  io.value("dynamic_increments", r.dynamicIncrements);
  io.number("settle_time", "s", r.settleTime);
  io.value("settle_steps", r.settleSteps);
  io.value("settled", r.settled);
  io.number("settle_kinetic", "J", r.settleKinetic);
  io.number("settle_max_time", "s", r.settleMaxTime);
  io.value("sunk_while_settling", r.sunkWhileSettling);
  io.number("wall_seconds", "", r.wallSeconds);
  io.value("samples", r.samples);
  io.value("snapshots", r.snapshots);
}

// Every field of summary.json, once, for both directions (the stop reason by its name).
template <class Io>
void serializeSummary(const Io& io, RunSummary& s) {
  io.value("generator", s.generator);
  io.value("scene", s.scene);
  io.value("bundle", s.bundle);
  io.value("target", s.target);
  std::string reason = Io::reading ? std::string() : stopReasonName(s.stopReason);
  io.value("stop_reason", reason);
  if (Io::reading) {
    const std::optional<StopReason> parsed = parseStopReason(reason);
    if (!parsed) throw InputError("summary.json: 'stop_reason' is \"" + reason + "\", which no run writes");
    s.stopReason = *parsed;
  }
  io.value("state_digest", s.stateDigest);
  io.object("response", [&](const auto& o) { serializeResponse(o, s); });
  io.object("material", [&](const auto& o) { serializeMaterial(o, s.material); });
  io.list("shapes", s.shapes, [](const auto& o, SummaryShape& shape) {
    o.value("name", shape.name);
    o.value("level_set", shape.levelSet);
    o.number("voxel", "mm", shape.voxel);
    o.number("node_spacing", "mm", shape.nodeSpacing);
    o.number("edge_node_spacing", "mm", shape.edgeNodeSpacing);
    o.value("nodes", shape.nodes);
  });
  io.object("run", [&](const auto& o) { serializeRun(o, s.run); });
}

}  // namespace

RunSummary makeRunSummary(const Scene& scene, const Bundle& bundle, const ContactParameters& contact,
                          const IndentationRecord& record, const ResponseParameters& response,
                          const RunProvenance& provenance) {
  RunSummary s;
  s.generator = generatorVersion();
  s.scene = scene.path;
  s.bundle = scene.bundle;
  s.target = record.targetName;
  s.stopReason = record.stopReason;
  s.stateDigest = provenance.stateDigest;
  s.response = response;
  s.fallen = record.fallen;
  s.failureLoadFraction = scene.protocol.failureLoadFraction;
  s.quasiStaticTarget = scene.protocol.quasiStaticTarget;
  s.deltaMax = record.deltaMax;
  SummaryMaterial& m = s.material;
  m.youngsModulus = contact.youngsModulus;
  m.friction = contact.friction;
  m.normalStiffness = contact.normalStiffness();
  m.tangentialStiffness = contact.tangentialStiffness();
  m.indenterStiffnessFactor = scene.indenter.stiffnessFactor;
  m.indenterRadius = record.indenterRadius;
  m.indenterSpeed = record.indenterSpeed;
  m.spanLength = contact.spanLength;
  m.spanInterfaces = contact.spanInterfaces;
  m.contactEvaluation = contact.evaluation == ContactEvaluation::OneWay ? "one-way" : "two-way";
  m.contactArea = contact.area == ContactArea::Nearest ? "nearest" : "blended";
  m.stiffnessRule = stiffnessRuleName(contact.stiffnessRule);
  for (const Shape& shape : bundle.shapes)
    s.shapes.push_back({shape.name, levelSetPath(shape, scene.solver.exactConvexLevelSets, scene.solver.exactMeshLevelSets),
                        shape.resolution.voxelSize, shape.resolution.nodeSpacing,
                        shape.resolution.edgeSpacingFraction * shape.resolution.nodeSpacing, static_cast<long>(shape.nodes.size())});
  SummaryRun& r = s.run;
  r.method = record.implicit ? "implicit" : "explicit";
  r.timeStep = record.timeStep;
  r.steps = record.steps;
  r.newtonIterations = record.implicitCounts.iterations;
  r.cutbacks = record.implicitCounts.cutbacks;
  r.dynamicIncrements = record.implicitCounts.dynamicIncrements;
  r.settleTime = record.settleTime;
  r.settleSteps = record.settleSteps;
  r.settled = record.settled;
  r.settleKinetic = record.settleKinetic;
  r.settleMaxTime = record.settleMaxTime;
  r.sunkWhileSettling = record.sunkWhileSettling;
  r.wallSeconds = record.wallSeconds;
  r.samples = static_cast<long>(record.curve.size());
  r.snapshots = static_cast<long>(record.snapshots.size());
  return s;
}

nlohmann::json runSummaryJson(const RunSummary& summary, bool withUnits) {
  nlohmann::json j = nlohmann::json::object();
  serializeSummary(JsonOut{j, withUnits}, const_cast<RunSummary&>(summary));  // a JsonOut only reads the fields
  return j;
}

RunSummary parseRunSummary(const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(std::string("summary.json: not JSON (") + e.what() + "); run the case again");
  }
  if (!j.is_object()) throw InputError("summary.json: not a JSON object");
  RunSummary s;
  serializeSummary(JsonIn{j, ""}, s);
  return s;
}

RunSummary readRunSummary(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "summary.json";
  try {
    return parseRunSummary(readTextFile(file.string()));
  } catch (const InputError& e) {
    const std::string what = e.what();  // parseRunSummary's begin "summary.json": name the whole path
    if (what.rfind("summary.json:", 0) != 0) throw;
    throw InputError(file.string() + what.substr(12));
  }
}

}  // namespace tessera

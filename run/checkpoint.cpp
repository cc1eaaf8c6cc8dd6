#include "run/checkpoint.h"

#include "io/file_digest.h"
#include "io/input_error.h"
#include "io/hdf5_file.h"
#include "run/curve_table.h"
#include "run/snapshot_table.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace tessera {

namespace fs = std::filesystem;
using h5::Handle;

namespace {

constexpr const char* kFormat = "tessera-checkpoint";
// 8: `fixed` marks the supports only (a retired body was marked fixed too in 7, which a version-7
// reader would need to keep it still). Version 7 files are read: their supports are the bundle's.
// 9: the indenter's work is `external_work`, the curve's and summary's name (7 and 8 call it
// `obstacle_work`, and are read under it).
constexpr std::int64_t kVersion = 9;
constexpr std::int64_t kOldestVersion = 7;

hsize_t count(std::size_t n) { return static_cast<hsize_t>(n); }

void writeVectors(hid_t g, const std::string& name, const std::vector<Eigen::Vector3d>& v) {
  std::vector<double> flat;
  for (const auto& x : v) flat.insert(flat.end(), {x.x(), x.y(), x.z()});
  h5::writeDataset(g, name, flat, {count(v.size()), 3});
}

std::vector<Eigen::Vector3d> readVectors(hid_t g, const std::string& name) {
  const auto flat = h5::readDataset<double>(g, name);
  if (flat.size() % 3 != 0) throw std::runtime_error("'" + name + "' is not a list of 3-vectors");
  std::vector<Eigen::Vector3d> v(flat.size() / 3);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = Eigen::Vector3d(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  return v;
}

void writeQuaternions(hid_t g, const std::string& name, const std::vector<Eigen::Quaterniond>& q) {
  std::vector<double> flat;
  for (const auto& x : q) flat.insert(flat.end(), {x.w(), x.x(), x.y(), x.z()});
  h5::writeDataset(g, name, flat, {count(q.size()), 4});
}

std::vector<Eigen::Quaterniond> readQuaternions(hid_t g, const std::string& name) {
  const auto flat = h5::readDataset<double>(g, name);
  if (flat.size() % 4 != 0) throw std::runtime_error("'" + name + "' is not a list of quaternions");
  std::vector<Eigen::Quaterniond> q(flat.size() / 4);
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = Eigen::Quaterniond(flat[4 * i], flat[4 * i + 1], flat[4 * i + 2], flat[4 * i + 3]);
  return q;
}

void writeFlags(hid_t g, const std::string& name, const std::vector<char>& f) {
  h5::writeDataset(g, name, std::vector<std::uint8_t>(f.begin(), f.end()), {count(f.size())});
}

std::vector<char> readFlags(hid_t g, const std::string& name) {
  const auto f = h5::readDataset<std::uint8_t>(g, name);
  return std::vector<char>(f.begin(), f.end());
}

void writeDoubles(hid_t g, const std::string& name, const std::vector<double>& v) { h5::writeDataset(g, name, v, {count(v.size())}); }

// The indenters and the contact pairs as flat tables (one row per sphere, per pair, per node
// contact), the form they take in the file.
struct SphereTable {
  std::vector<Eigen::Vector3d> centre, velocity;
  std::vector<double> radius, factor;
};

SphereTable tableOf(const std::vector<SphereObstacle>& spheres) {
  SphereTable t;
  for (const SphereObstacle& s : spheres) {
    t.centre.push_back(s.center);
    t.velocity.push_back(s.velocity);
    t.radius.push_back(s.radius);
    t.factor.push_back(s.stiffnessFactor);
  }
  return t;
}

std::vector<SphereObstacle> spheresOf(const SphereTable& t) {
  if (t.radius.size() != t.centre.size() || t.factor.size() != t.centre.size() || t.velocity.size() != t.centre.size())
    throw std::runtime_error("inconsistent indenter records");
  std::vector<SphereObstacle> spheres;
  for (std::size_t k = 0; k < t.centre.size(); ++k) spheres.push_back({t.centre[k], t.radius[k], t.velocity[k], t.factor[k]});
  return spheres;
}

struct PairTable {
  std::vector<std::int32_t> a, b, contacts;            // per pair
  std::vector<Eigen::Vector3d> forceA, torqueA, forceB, torqueB;
  std::vector<double> elastic, depth;
  std::vector<double> key, energy, area;               // per node contact (keys: whole numbers < 2^32)
  std::vector<Eigen::Vector3d> spring;
};

PairTable tableOf(const std::vector<PairState>& pairs) {
  PairTable t;
  for (const PairState& p : pairs) {
    t.a.push_back(p.a);
    t.b.push_back(p.b);
    t.contacts.push_back(static_cast<std::int32_t>(p.contacts.size()));
    for (const NodeContact& c : p.contacts) {
      t.key.push_back(static_cast<double>(c.key));
      t.spring.push_back(c.spring);
      t.energy.push_back(c.energy);
      t.area.push_back(c.area);
    }
    t.forceA.push_back(p.forceA);
    t.torqueA.push_back(p.torqueA);
    t.forceB.push_back(p.forceB);
    t.torqueB.push_back(p.torqueB);
    t.elastic.push_back(p.elastic);
    t.depth.push_back(p.depth);
  }
  return t;
}

// Every count and index is checked against the arrays before it is used.
std::vector<PairState> pairsOf(const PairTable& t) {
  const std::size_t n = t.a.size();
  if (t.b.size() != n || t.contacts.size() != n || t.forceA.size() != n || t.torqueA.size() != n || t.forceB.size() != n ||
      t.torqueB.size() != n || t.elastic.size() != n || t.depth.size() != n)
    throw std::runtime_error("inconsistent pair records");
  std::size_t total = 0;
  for (std::int32_t c : t.contacts) {
    if (c < 0) throw std::runtime_error("a negative contact count");
    total += static_cast<std::size_t>(c);
  }
  if (total != t.key.size() || t.spring.size() != total || t.energy.size() != total || t.area.size() != total)
    throw std::runtime_error("contact counts do not match the contact records");
  for (double key : t.key)
    if (!(key >= 0 && key < 4294967296.0 && key == std::floor(key))) throw std::runtime_error("a contact key out of range");
  std::vector<PairState> pairs;
  std::size_t next = 0;
  for (std::size_t p = 0; p < n; ++p) {
    PairState pair;
    pair.a = t.a[p];
    pair.b = t.b[p];
    for (int c = 0; c < t.contacts[p]; ++c, ++next)
      pair.contacts.push_back({static_cast<std::uint32_t>(t.key[next]), t.spring[next], t.energy[next], t.area[next]});
    pair.forceA = t.forceA[p];
    pair.torqueA = t.torqueA[p];
    pair.forceB = t.forceB[p];
    pair.torqueB = t.torqueB[p];
    pair.elastic = t.elastic[p];
    pair.depth = t.depth[p];
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

// The two directions of one list of fields (serializeWorld): a Writer stores each field under
// its name, a Reader fills it from there.
struct Writer {
  static constexpr bool reading = false;
  hid_t g;
  void field(const char* name, std::vector<Eigen::Vector3d>& v) const { writeVectors(g, name, v); }
  void field(const char* name, std::vector<Eigen::Quaterniond>& v) const { writeQuaternions(g, name, v); }
  void field(const char* name, std::vector<char>& v) const { writeFlags(g, name, v); }
  void field(const char* name, std::vector<double>& v) const { writeDoubles(g, name, v); }
  void field(const char* name, std::vector<std::int32_t>& v) const { h5::writeDataset(g, name, v, {count(v.size())}); }
  void field(const char* name, double& x) const { h5::writeAttribute(g, name, x); }
  void field(const char* name, long& x) const { h5::writeAttribute(g, name, std::int64_t{x}); }
  void field(const char* name, int& x) const { h5::writeAttribute(g, name, std::int64_t{x}); }
  void field(const char* name, bool& x) const { h5::writeAttribute(g, name, std::int64_t{x}); }
  void field(const char* name, std::string& x) const { h5::writeAttribute(g, name, x); }
  void field(const char* name, std::vector<CurveSample>& v) const { writeCurve(h5::createGroup(g, name).get(), v); }
  void field(const char* name, std::vector<Snapshot>& v) const {
    const std::vector<std::string> names(v.empty() ? 0 : v.front().position.size());  // not kept: the bundle has them
    writeSnapshots(h5::createGroup(g, name).get(), v, names);
  }
  void field(const char* name, std::vector<FallenBody>& v) const { writeFallen(h5::createGroup(g, name).get(), v); }
};

struct Reader {
  static constexpr bool reading = true;
  hid_t g;
  void field(const char* name, std::vector<Eigen::Vector3d>& v) const { v = readVectors(g, name); }
  void field(const char* name, std::vector<Eigen::Quaterniond>& v) const { v = readQuaternions(g, name); }
  void field(const char* name, std::vector<char>& v) const { v = readFlags(g, name); }
  void field(const char* name, std::vector<double>& v) const { v = h5::readDataset<double>(g, name); }
  void field(const char* name, std::vector<std::int32_t>& v) const { v = h5::readDataset<std::int32_t>(g, name); }
  void field(const char* name, double& x) const {
    // Versions before 9 kept the indenter's work under its former name.
    x = h5::readDoubleAttribute(g, version < 9 && std::string(name) == "external_work" ? "obstacle_work" : name);
  }
  void field(const char* name, long& x) const { x = static_cast<long>(h5::readIntAttribute(g, name)); }
  void field(const char* name, int& x) const { x = static_cast<int>(h5::readIntAttribute(g, name)); }
  void field(const char* name, bool& x) const { x = h5::readIntAttribute(g, name) != 0; }
  void field(const char* name, std::string& x) const { x = h5::readStringAttribute(g, name); }
  void field(const char* name, std::vector<CurveSample>& v) const { v = readCurve(h5::openGroup(g, name).get()); }
  void field(const char* name, std::vector<Snapshot>& v) const { v = readSnapshots(h5::openGroup(g, name).get(), bodies); }
  void field(const char* name, std::vector<FallenBody>& v) const { v = readFallen(h5::openGroup(g, name).get()); }
  std::size_t bodies = 0;  ///< the bundle's, which a snapshot's arrays must match
  std::int64_t version = kVersion;  ///< the file's format version
};

// Every field of a WorldState the checkpoint keeps, once, for both directions. (Masses, inertia,
// shapes and names come from the bundle; candidate node lists are rebuilt on resume.)
template <class Archive>
void serializeWorld(const Archive& io, WorldState& w) {
  io.field("position", w.bodies.position);
  io.field("orientation", w.bodies.orientation);
  io.field("velocity", w.bodies.velocity);
  io.field("angular_momentum", w.bodies.angularMomentum);
  io.field("fixed", w.bodies.fixed);
  io.field("retired", w.bodies.retired);
  SphereTable spheres = Archive::reading ? SphereTable{} : tableOf(w.spheres);
  io.field("sphere_centre", spheres.centre);
  io.field("sphere_velocity", spheres.velocity);
  io.field("sphere_radius", spheres.radius);
  io.field("sphere_stiffness_factor", spheres.factor);
  if (Archive::reading) w.spheres = spheresOf(spheres);
  PairTable pairs = Archive::reading ? PairTable{} : tableOf(w.pairs);
  io.field("pair_a", pairs.a);
  io.field("pair_b", pairs.b);
  io.field("pair_contacts", pairs.contacts);
  io.field("contact_key", pairs.key);
  io.field("contact_spring", pairs.spring);
  io.field("contact_energy", pairs.energy);
  io.field("contact_area", pairs.area);
  io.field("pair_force_a", pairs.forceA);
  io.field("pair_torque_a", pairs.torqueA);
  io.field("pair_force_b", pairs.forceB);
  io.field("pair_torque_b", pairs.torqueB);
  io.field("pair_elastic", pairs.elastic);
  io.field("pair_max_depth", pairs.depth);
  if (Archive::reading) w.pairs = pairsOf(pairs);
  io.field("built_position", w.builtPosition);
  io.field("built_orientation", w.builtOrientation);
  io.field("built_sphere_centre", w.builtSphereCentre);
  io.field("force", w.force);
  io.field("torque", w.torque);
  io.field("contact_force", w.contactForce);
  io.field("contact_torque", w.contactTorque);
  io.field("sphere_reaction", w.sphereReaction);
  io.field("damping_force", w.dampingForce);
  io.field("damping_torque", w.dampingTorque);
  io.field("start_position", w.startPosition);
  io.field("pairs_valid", w.pairsValid);
  io.field("forces_valid", w.forcesValid);
  io.field("initial_energy", w.initialEnergy);
  io.field("external_work", w.externalWork);
  io.field("friction_dissipated", w.friction);
  io.field("damping_dissipated", w.damping);
  io.field("retired_kinetic", w.retiredKinetic);
  io.field("projection_energy", w.projection);
  io.field("most_supplied", w.mostSupplied);
  io.field("time", w.time);
  io.field("steps", w.steps);
  io.field("implicit_increment", w.implicit.increment);
  io.field("implicit_travel_factor", w.implicit.travelFactor);
  io.field("implicit_largest_reaction", w.implicit.largestReaction);
  io.field("implicit_iterations", w.implicit.iterations);
  io.field("implicit_cutbacks", w.implicit.cutbacks);
  io.field("implicit_dynamic_increments", w.implicit.dynamicIncrements);
}

void writeWorld(hid_t g, const WorldState& w) {
  serializeWorld(Writer{g}, const_cast<WorldState&>(w));  // a Writer only reads the fields
}

void readWorld(hid_t g, WorldState& w, std::int64_t version) {
  Reader reader{g};
  reader.version = version;
  serializeWorld(reader, w);
}

// Every field of the protocol's state and record the checkpoint keeps, once, for both directions
// (the stop reason by its name).
template <class Archive>
void serializeRecord(const Archive& io, IndentationState& s, IndentationRecord& r) {
  io.field("phase", s.phase);
  io.field("sphere", s.sphere);
  io.field("load_start", s.loadStart);
  io.field("contact_travel", s.contactTravel);
  io.field("peak", s.peak);
  io.field("next_sample", s.nextSample);
  io.field("next_snapshot", s.nextSnapshot);
  io.field("quiet_from", s.quietFrom);
  io.field("travel_base", s.travelBase);
  io.field("path_base", s.pathBase);
  io.field("speed_since", s.speedSince);
  io.field("contact_path", s.contactPath);
  io.field("rate_adapted", s.rateAdapted);
  io.field("settled_position", s.settledPosition);
  io.field("out_at", s.outAt);
  io.field("settle_time", r.settleTime);
  io.field("settle_steps", r.settleSteps);
  io.field("settled", r.settled);
  io.field("sunk_while_settling", r.sunkWhileSettling);
  io.field("target", r.target);
  io.field("target_name", r.targetName);
  io.field("thickness", r.thickness);
  io.field("delta_max", r.deltaMax);
  std::string reason = Archive::reading ? std::string() : std::string(stopReasonName(r.stopReason));
  io.field("stop_reason", reason);
  if (Archive::reading) {
    const std::optional<StopReason> parsed = parseStopReason(reason);
    if (!parsed) throw std::runtime_error("protocol state: a stop reason the protocol does not give");
    r.stopReason = *parsed;
  }
  io.field("steps", r.steps);
  io.field("time_step", r.timeStep);
  io.field("wall_seconds", r.wallSeconds);
  io.field("curve", r.curve);
  io.field("snapshots", r.snapshots);
  io.field("fallen", r.fallen);
}

void writeRecord(hid_t g, const IndentationState& s, const IndentationRecord& r) {
  serializeRecord(Writer{g}, const_cast<IndentationState&>(s), const_cast<IndentationRecord&>(r));  // a Writer only reads the fields
}

// The protocol state's numbers, each against what the protocol can have made of it: a damaged
// value would resume with exit 0 and label the results wrongly.
void checkProtocolValues(const IndentationState& s, const IndentationRecord& r) {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::runtime_error(std::string("protocol state: ") + what);
  };
  for (double x : {s.loadStart, s.contactTravel, s.peak, s.nextSample, s.nextSnapshot, s.quietFrom, s.travelBase, s.pathBase,
                   s.speedSince, s.contactPath, r.settleTime, r.thickness, r.deltaMax, r.timeStep, r.wallSeconds})
    require(std::isfinite(x), "a value that is not finite");
  for (const Eigen::Vector3d& x : s.settledPosition) require(x.allFinite(), "a settled position that is not finite");
  for (double x : s.outAt) require(std::isfinite(x), "a body's fall deflection that is not finite");
  require(s.loadStart >= 0 && s.speedSince >= s.loadStart && s.peak >= 0 && s.nextSample >= 0 && s.nextSnapshot >= 0,
          "a time, load or sampling point out of range");
  require(r.settleTime >= 0 && r.timeStep >= 0 && r.wallSeconds >= 0 && r.steps >= 0 && r.settleSteps >= 0,
          "a time or step count out of range");
  if (s.phase > 0)
    require(r.thickness > 0 && r.deltaMax > 0, "the loaded block's thickness or delta_max is not positive");
  // The first sample is taken at first contact, and every later one moves next_sample on.
  require(s.contactTravel < 0 || !r.curve.empty(), "contact was made but the curve is empty");
  require(s.nextSample == 0 || !r.curve.empty(), "samples were taken but the curve is empty");
}

void readRecord(hid_t g, IndentationState& s, IndentationRecord& r, std::size_t bodies) {
  Reader reader{g};
  reader.bodies = bodies;
  serializeRecord(reader, s, r);
  if ((s.phase > 0 && s.settledPosition.size() != bodies) || s.outAt.size() != s.settledPosition.size())
    throw std::runtime_error("settled positions for a different number of bodies");
  if (s.phase < 0 || s.phase > 2 || r.target < -1 || r.target >= static_cast<int>(bodies) || (s.phase > 0 && r.target < 0) ||
      (s.phase > 0 && s.sphere < 0))
    throw std::runtime_error("protocol state out of range");
  checkProtocolValues(s, r);
}

}  // namespace

void writeCheckpoint(const std::string& path, const CheckpointSource& source, const WorldState& world,
                     const IndentationState& state, const IndentationRecord& record) {
  h5::writeFile(fs::path(path), [&](hid_t f) {
    h5::writeAttribute(f, "format", std::string(kFormat));
    h5::writeAttribute(f, "format_version", kVersion);
    h5::writeAttribute(f, "generator", generatorVersion());
    h5::writeAttribute(f, "scene", source.scene);
    h5::writeAttribute(f, "scene_text", source.sceneText);
    h5::writeAttribute(f, "scene_text_digest", textDigest(source.sceneText));
    h5::writeAttribute(f, "scene_digest", source.sceneDigest);
    h5::writeAttribute(f, "preset", source.preset);
    h5::writeAttribute(f, "bundle", source.bundle);
    h5::writeAttribute(f, "bundle_relative", source.bundleRelative);
    h5::writeAttribute(f, "bundle_digest", source.bundleDigest);
    h5::writeAttribute(f, "threads", std::int64_t{source.threads});
    Handle w = h5::createGroup(f, "world");
    writeWorld(w.get(), world);
    Handle r = h5::createGroup(f, "run");
    writeRecord(r.get(), state, record);
  });
}

CheckpointSource readCheckpointSource(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path + ": no checkpoint to resume from (a run writes checkpoint.h5 into its output directory)");
  try {
    Handle f = h5::openFileReadOnly(path);
    if (h5::readStringAttribute(f.get(), "format") != kFormat) throw InputError(path + ": not a Tessera checkpoint");
    const auto version = h5::readIntAttribute(f.get(), "format_version");
    if (version < kOldestVersion || version > kVersion)
      throw InputError(path + ": checkpoint format version " + std::to_string(version) + " is not supported (this " +
                       generatorVersion() + " reads versions " + std::to_string(kOldestVersion) + " to " + std::to_string(kVersion) +
                       "; run it again from the scene)");
    CheckpointSource s;
    s.scene = h5::readStringAttribute(f.get(), "scene");
    s.sceneText = h5::readStringAttribute(f.get(), "scene_text");
    if (textDigest(s.sceneText) != h5::readStringAttribute(f.get(), "scene_text_digest"))
      throw std::runtime_error("the scene's text is not the one the run started with");
    s.sceneDigest = h5::readStringAttribute(f.get(), "scene_digest");
    s.preset = h5::readStringAttribute(f.get(), "preset");
    s.bundle = h5::readStringAttribute(f.get(), "bundle");
    s.bundleRelative = h5::readStringAttribute(f.get(), "bundle_relative");
    s.bundleDigest = h5::readStringAttribute(f.get(), "bundle_digest");
    s.threads = static_cast<int>(h5::readIntAttribute(f.get(), "threads"));
    if (s.threads < 0 || s.threads > 4096) throw std::runtime_error("thread count out of range");
    return s;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path + ": corrupt checkpoint (" + e.what() + "); " + kUnreadableCheckpointFix);
  }
}

void readCheckpoint(const std::string& path, WorldState& world, IndentationState& state, IndentationRecord& record) {
  try {
    Handle f = h5::openFileReadOnly(path);
    Handle w = h5::openGroup(f.get(), "world");
    const std::size_t bodies = world.bodies.size();
    const std::vector<char> fixedInBundle = world.bodies.fixed;
    readWorld(w.get(), world, h5::readIntAttribute(f.get(), "format_version"));
    if (world.bodies.position.size() != bodies) throw std::runtime_error("it holds a different number of bodies than the bundle");
    // The supports are the bundle's (a checkpoint written before retired bodies had their own
    // flag marks them fixed too).
    if (world.bodies.fixed.size() == bodies) world.bodies.fixed = fixedInBundle;
    Handle r = h5::openGroup(f.get(), "run");
    readRecord(r.get(), state, record, bodies);
    if (state.sphere < -1 || state.sphere >= static_cast<int>(world.spheres.size()) || (state.phase > 0 && state.sphere < 0))
      throw std::runtime_error("the indenter's index is out of range");
    if (record.target >= 0 && (fixedInBundle[record.target] || world.bodies.name[record.target] != record.targetName))
      throw std::runtime_error("the loaded block is not the bundle's free body '" + record.targetName + "'");
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot resume from this checkpoint (" + e.what() + "); " + kUnreadableCheckpointFix);
  }
}

}  // namespace tessera

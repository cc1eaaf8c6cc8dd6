#include "run/snapshot_table.h"

#include "io/hdf5_file.h"

#include <stdexcept>

namespace tessera {

namespace {

// A dataset of `dims` with its unit (and, where it helps, a note on what it holds).
template <class T>
void writeWithUnit(hid_t g, const std::string& name, const std::vector<T>& data, const std::vector<hsize_t>& dims,
                   const std::string& unit, const std::string& note = "") {
  h5::writeDataset(g, name, data, dims);
  h5::writeDatasetAttribute(g, name, "unit", unit);
  if (!note.empty()) h5::writeDatasetAttribute(g, name, "note", note);
}

void append(std::vector<double>& flat, const Eigen::Vector3d& v) { flat.insert(flat.end(), {v.x(), v.y(), v.z()}); }

Eigen::Vector3d vectorAt(const std::vector<double>& flat, std::size_t i) {
  return {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
}

// A dataset read and required to hold `size` values.
template <class T>
std::vector<T> readSized(hid_t g, const char* name, std::size_t size) {
  std::vector<T> v = h5::readDataset<T>(g, name);
  if (v.size() != size) throw std::runtime_error(std::string("inconsistent snapshot records (") + name + ")");
  return v;
}

}  // namespace

void writeSnapshots(hid_t g, const std::vector<Snapshot>& snapshots, const std::vector<std::string>& bodyNames) {
  h5::writeStrings(g, "body_names", bodyNames);
  std::vector<double> delta, load, position, orientation, velocity, indenter;
  std::vector<std::int32_t> offset{0}, pair, nodes, slidingNodes;
  std::vector<double> point, force, normal, tangential, area, sliding, stiffness;
  for (const Snapshot& s : snapshots) {
    delta.push_back(s.delta);
    load.push_back(s.load);
    for (const Eigen::Vector3d& x : s.position) append(position, x);
    for (const Eigen::Quaterniond& q : s.orientation) orientation.insert(orientation.end(), {q.w(), q.x(), q.y(), q.z()});
    for (const Eigen::Vector3d& v : s.velocity) append(velocity, v);
    append(indenter, s.indenter);
    for (const ForceLink& l : s.forces) {
      pair.insert(pair.end(), {l.a, l.b});
      append(point, l.point);
      append(force, l.force);
      append(normal, l.normalForce);
      append(tangential, l.force - l.normalForce);
      nodes.push_back(l.nodeContacts);
      slidingNodes.push_back(l.slidingNodes);
      area.push_back(l.area);
      stiffness.push_back(l.normalStiffness);
      sliding.push_back(l.nodeContacts > 0 ? static_cast<double>(l.slidingNodes) / l.nodeContacts : 0.0);
    }
    offset.push_back(static_cast<std::int32_t>(pair.size() / 2));
  }
  const hsize_t frames = snapshots.size(), bodies = bodyNames.size(), links = pair.size() / 2;
  writeWithUnit(g, "delta", delta, {frames}, "m");
  writeWithUnit(g, "load", load, {frames}, "N");
  writeWithUnit(g, "position", position, {frames, bodies, 3}, "m", "each body's centroid");
  writeWithUnit(g, "orientation", orientation, {frames, bodies, 4}, "1", "unit quaternion (w, x, y, z), body frame to world");
  writeWithUnit(g, "velocity", velocity, {frames, bodies, 3}, "m/s", "each body's centroid");
  writeWithUnit(g, "indenter", indenter, {frames, 3}, "m", "the indenter's centre");
  writeWithUnit(g, "force_offset", offset, {offset.size()}, "1", "snapshot k's contacts are rows offset[k] to offset[k+1]-1");
  writeWithUnit(g, "force_pair", pair, {links, 2}, "1", "bodies (a, b) by index into body_names; b = -1: the indenter");
  writeWithUnit(g, "force_point", point, {links, 3}, "m", "contact points weighted by normal force");
  writeWithUnit(g, "force", force, {links, 3}, "N", "the pair's contact force on a");
  writeWithUnit(g, "force_normal", normal, {links, 3}, "N", "its part along the contact normals");
  writeWithUnit(g, "force_tangential", tangential, {links, 3}, "N", "its friction part: force - force_normal");
  writeWithUnit(g, "force_node_contacts", nodes, {links}, "count", "node contacts of the pair");
  writeWithUnit(g, "force_sliding_nodes", slidingNodes, {links}, "count", "of them, at the Coulomb cap");
  writeWithUnit(g, "force_sliding_fraction", sliding, {links}, "1", "force_sliding_nodes / force_node_contacts");
  writeWithUnit(g, "force_area", area, {links}, "m^2", "their effective (projected) area");
  writeWithUnit(g, "force_normal_stiffness", stiffness, {links}, "N/m^3", "the pair's k_n (material.stiffness_rule)");
}

std::vector<Snapshot> readSnapshots(hid_t g, std::size_t bodies) {
  const auto delta = h5::readDataset<double>(g, "delta");
  const std::size_t frames = delta.size();
  const auto load = readSized<double>(g, "load", frames);
  const auto position = readSized<double>(g, "position", 3 * frames * bodies);
  const auto orientation = readSized<double>(g, "orientation", 4 * frames * bodies);
  const auto velocity = readSized<double>(g, "velocity", 3 * frames * bodies);
  const auto indenter = readSized<double>(g, "indenter", 3 * frames);
  const auto offset = readSized<std::int32_t>(g, "force_offset", frames + 1);
  if (offset[0] != 0) throw std::runtime_error("inconsistent snapshot records (force_offset)");
  for (std::size_t k = 0; k < frames; ++k)
    if (offset[k + 1] < offset[k]) throw std::runtime_error("inconsistent snapshot records (force_offset)");
  const std::size_t links = static_cast<std::size_t>(offset[frames]);
  const auto pair = readSized<std::int32_t>(g, "force_pair", 2 * links);
  const auto point = readSized<double>(g, "force_point", 3 * links);
  const auto force = readSized<double>(g, "force", 3 * links);
  const auto normal = readSized<double>(g, "force_normal", 3 * links);
  const auto nodes = readSized<std::int32_t>(g, "force_node_contacts", links);
  const auto sliding = readSized<std::int32_t>(g, "force_sliding_nodes", links);
  const auto area = readSized<double>(g, "force_area", links);
  // Absent from records written before per-pair stiffnesses: read as 0 (not known).
  const auto stiffness = H5Lexists(g, "force_normal_stiffness", H5P_DEFAULT) > 0
                             ? readSized<double>(g, "force_normal_stiffness", links)
                             : std::vector<double>(links, 0.0);
  for (std::int32_t body : pair)
    if (body < -64 || body >= static_cast<std::int32_t>(bodies)) throw std::runtime_error("a contact record names no body");
  std::vector<Snapshot> snapshots;
  for (std::size_t k = 0; k < frames; ++k) {
    Snapshot s;
    s.delta = delta[k];
    s.load = load[k];
    for (std::size_t i = 0; i < bodies; ++i) {
      const std::size_t at = k * bodies + i;
      s.position.push_back(vectorAt(position, at));
      s.orientation.emplace_back(orientation[4 * at], orientation[4 * at + 1], orientation[4 * at + 2], orientation[4 * at + 3]);
      s.velocity.push_back(vectorAt(velocity, at));
    }
    s.indenter = vectorAt(indenter, k);
    for (auto l = static_cast<std::size_t>(offset[k]); l < static_cast<std::size_t>(offset[k + 1]); ++l)
      s.forces.push_back({pair[2 * l], pair[2 * l + 1], vectorAt(point, l), vectorAt(force, l), vectorAt(normal, l), nodes[l],
                          area[l], sliding[l], stiffness[l]});
    snapshots.push_back(std::move(s));
  }
  return snapshots;
}

void writeFallen(hid_t g, const std::vector<FallenBody>& fallen) {
  std::vector<std::string> names;
  std::vector<double> delta;
  std::vector<std::uint8_t> retired, touching;
  for (const FallenBody& b : fallen) {
    names.push_back(b.name);
    delta.push_back(b.delta);
    retired.push_back(b.retired);
    touching.push_back(b.touching);
  }
  h5::writeStrings(g, "names", names);
  writeWithUnit(g, "delta", delta, {delta.size()}, "m", "indenter travel when it left the assembly");
  writeWithUnit(g, "retired", retired, {retired.size()}, "1", "taken out of the computation");
  writeWithUnit(g, "touching", touching, {touching.size()}, "1", "pushed through, still touching blocks");
}

std::vector<FallenBody> readFallen(hid_t g) {
  const auto names = h5::readStrings(g, "names");
  const auto delta = readSized<double>(g, "delta", names.size());
  const auto retired = readSized<std::uint8_t>(g, "retired", names.size());
  const auto touching = readSized<std::uint8_t>(g, "touching", names.size());
  std::vector<FallenBody> fallen;
  for (std::size_t i = 0; i < names.size(); ++i) fallen.push_back({names[i], delta[i], retired[i] != 0, touching[i] != 0});
  return fallen;
}

}  // namespace tessera

#include "run/run_output.h"
#include "io/json_text.h"

#include "io/safe_write.h"
#include "levelset/assembly_export.h"
#include "io/hdf5_file.h"
#include "run/curve_table.h"
#include "run/paraview_state.h"
#include "run/run_summary.h"
#include "run/snapshot_table.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace tessera {

namespace fs = std::filesystem;

namespace {

void writeResultsH5(hid_t f, const Scene& scene, const Bundle& bundle, const ContactParameters& contact,
                    const IndentationRecord& record, const RunProvenance& provenance) {
  h5::writeAttribute(f, "format", std::string("tessera-results"));
  h5::writeAttribute(f, "format_version", std::int64_t{3});
  h5::writeAttribute(f, "generator", generatorVersion());
  h5::writeAttribute(f, "scene_file", scene.path);
  h5::writeAttribute(f, "scene_text", provenance.sceneText);
  h5::writeAttribute(f, "state_digest", provenance.stateDigest);
  h5::writeAttribute(f, "bundle", scene.bundle);
  h5::writeAttribute(f, "bundle_generator", bundle.generator);
  h5::writeAttribute(f, "units", std::string("SI: m, N, J, s, kg; attribute 'unit' on every dataset"));
  h5::writeAttribute(f, "youngs_modulus", contact.youngsModulus);
  h5::writeAttribute(f, "normal_stiffness", contact.normalStiffness());
  h5::writeAttribute(f, "friction", contact.friction);
  h5::writeAttribute(f, "time_step", record.timeStep);
  h5::writeAttribute(f, "stop_reason", std::string(stopReasonName(record.stopReason)));
  h5::writeAttribute(f, "solver_method", std::string(record.implicit ? "implicit" : "explicit"));
  h5::writeAttribute(f, "steps", std::int64_t{record.steps});
  h5::writeAttribute(f, "newton_iterations", std::int64_t{record.implicitCounts.iterations});
  h5::writeAttribute(f, "cutbacks", std::int64_t{record.implicitCounts.cutbacks});
  h5::writeAttribute(f, "dynamic_increments", std::int64_t{record.implicitCounts.dynamicIncrements});

  h5::writeAttribute(f, "target", record.targetName);
  h5::writeAttribute(f, "thickness", record.thickness);
  writeCurve(h5::createGroup(f, "curve").get(), record.curve);

  std::vector<std::string> names;
  for (const Body& b : bundle.bodies) names.push_back(b.name);
  writeSnapshots(h5::createGroup(f, "snapshots").get(), record.snapshots, names);
  writeFallen(h5::createGroup(f, "fallen").get(), record.fallen);
}

}  // namespace

void writeSweepTable(const std::string& path, const std::vector<std::string>& keys,
                     const std::vector<std::vector<double>>& values, const std::vector<std::string>& columns,
                     const std::vector<std::vector<double>>& table, const std::vector<std::string>& cases,
                     const std::vector<std::string>& failureModes, const std::vector<std::string>& stopReasons) {
  h5::writeFile(fs::path(path), [&](hid_t f) {
    h5::writeAttribute(f, "format", std::string("tessera-sweep"));
    h5::writeAttribute(f, "generator", generatorVersion());
    h5::writeStrings(f, "keys", keys);
    h5::writeStrings(f, "columns", columns);
    std::vector<double> v, t;
    for (const auto& row : values) v.insert(v.end(), row.begin(), row.end());
    for (const auto& row : table) t.insert(t.end(), row.begin(), row.end());
    h5::writeDataset(f, "values", v, {values.size(), keys.size()});
    h5::writeDataset(f, "table", t, {table.size(), columns.size()});
    h5::writeStrings(f, "case", cases);
    h5::writeStrings(f, "failure_mode", failureModes);
    h5::writeStrings(f, "stop_reason", stopReasons);
  });
}

namespace {

// curve.csv: one row per curve sample, lengths in mm (docs/outputs.md).
void writeCurveCsv(const fs::path& dir, const IndentationRecord& record) {
  std::string out =
      "delta_mm,load_N,time_s,kinetic_J,external_work_J,contacts,block_displacement_mm,indenter_penetration_mm,"
         "sliding_fraction,loaded_sliding_fraction\n";
  char line[320];
  for (const CurveSample& s : record.curve) {
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.0f,%.17g,%.17g,%.17g,%.17g\n", s.delta * 1e3, s.load,
                  s.time, s.kinetic, s.externalWork, s.contacts, s.blockDisplacement * 1e3, s.indenterPenetration * 1e3,
                  s.blockContacts > 0 ? s.slidingContacts / s.blockContacts : 0.0,
                  s.loadedContacts > 0 ? s.loadedSliding / s.loadedContacts : 0.0);
    out += line;
  }
  writeTextFileSafely(dir / "curve.csv", out);
}

// The ParaView series: per snapshot the blocks (displacement from the bundle's pose, velocity),
// the contacts as points at their force centres, and the indenter; each part as its own series
// too, and a ParaView state that opens them ready to look at.
void writeParaViewSeries(const fs::path& dir, const Bundle& bundle, const IndentationRecord& record) {
  std::vector<Eigen::Vector3d> built;
  for (const Body& b : bundle.bodies) built.push_back(b.position);
  // ParaView's time axis: delta in mm, or the snapshot's number when the indenter went back up.
  bool rising = true;
  for (std::size_t k = 1; k < record.snapshots.size(); ++k) rising = rising && record.snapshots[k].delta > record.snapshots[k - 1].delta;
  std::vector<std::string> files;
  std::vector<double> times;
  for (std::size_t k = 0; k < record.snapshots.size(); ++k) {
    const Snapshot& s = record.snapshots[k];
    char blocks[48], forces[48], indenter[48];
    std::snprintf(blocks, sizeof blocks, "blocks_%04zu.vtu", k);
    std::snprintf(forces, sizeof forces, "forces_%04zu.vtu", k);
    std::snprintf(indenter, sizeof indenter, "indenter_%04zu.vtu", k);
    // Frames are final once written (a resumed run writes the same ones): write each once.
    if (!fs::exists(dir / "paraview" / blocks)) {
      std::vector<Eigen::Vector3d> displacement(s.position.size());
      for (std::size_t i = 0; i < s.position.size(); ++i) displacement[i] = s.position[i] - built[i];
      writeBlocksVtu(bundle, s.position, s.orientation, (dir / "paraview" / blocks).string(),
                     {{"displacement", displacement}, {"velocity", s.velocity}});
    }
    if (!fs::exists(dir / "paraview" / forces)) {
      std::vector<Eigen::Vector3d> point, force, normal, tangential;
      std::vector<double> magnitude, a, b, nodes, area, sliding;
      for (const ForceLink& l : s.forces) {
        point.push_back(l.point);
        force.push_back(l.force);
        normal.push_back(l.normalForce);
        tangential.push_back(l.force - l.normalForce);
        magnitude.push_back(l.force.norm());
        a.push_back(l.a);
        b.push_back(l.b);
        nodes.push_back(l.nodeContacts);
        area.push_back(l.area);
        sliding.push_back(l.nodeContacts > 0 ? static_cast<double>(l.slidingNodes) / l.nodeContacts : 0.0);
      }
      writePointsVtu((dir / "paraview" / forces).string(), point,
                     {{"force", force}, {"normal_force", normal}, {"tangential_force", tangential}},
                     {{"magnitude", magnitude}, {"body_a", a}, {"body_b", b}, {"node_contacts", nodes}, {"area", area},
                      {"sliding_fraction", sliding}});
    }
    if (!fs::exists(dir / "paraview" / indenter))
      writeSphereVtu(s.indenter, record.indenterRadius, (dir / "paraview" / indenter).string());
    files.insert(files.end(), {blocks, forces, indenter});
    times.insert(times.end(), 3, rising ? s.delta * 1e3 : static_cast<double>(k));
  }
  writePvd((dir / "paraview" / "slab.pvd").string(), files, times);
  // Each part as its own series too, and a ParaView state that opens them ready to look at.
  for (const std::size_t part : {0, 1, 2}) {
    std::vector<std::string> partFiles;
    std::vector<double> partTimes;
    for (std::size_t i = part; i < files.size(); i += 3) {
      partFiles.push_back(files[i]);
      partTimes.push_back(times[i]);
    }
    writePvd((dir / "paraview" / (std::string(part == 0 ? "blocks" : part == 1 ? "forces" : "indenter") + ".pvd")).string(),
             partFiles, partTimes);
  }
  double largestForce = 0, largestDisplacement = 0;
  for (const Snapshot& s : record.snapshots) {
    for (const ForceLink& l : s.forces) largestForce = std::max(largestForce, l.force.norm());
    for (std::size_t i = 0; i < s.position.size(); ++i)
      largestDisplacement = std::max(largestDisplacement, (s.position[i] - built[i]).norm());
  }
  writeParaViewState((dir / "paraview").string(),
                     {largestForce > 0 ? 3 * record.thickness / largestForce : 0.0, record.thickness, largestDisplacement});
}

}  // namespace

void writeRunOutputs(const std::string& directory, const Scene& scene, const Bundle& bundle,
                     const ContactParameters& contact, const IndentationRecord& record,
                     const ResponseParameters& response, const RunProvenance& provenance) {
  const fs::path dir(directory);
  fs::create_directories(dir / "paraview");
  h5::writeFile(dir / "results.h5", [&](hid_t f) { writeResultsH5(f, scene, bundle, contact, record, provenance); });
  writeCurveCsv(dir, record);
  writeParaViewSeries(dir, bundle, record);
  // Last: a summary.json that says how the run stopped means every file above was written then
  // (a resumed run that had finished relies on it, RunSession::finishedAndWritten).
  writeTextFileSafely(dir / "summary.json", jsonText(runSummaryJson(makeRunSummary(scene, bundle, contact, record, response, provenance))));
}

}  // namespace tessera

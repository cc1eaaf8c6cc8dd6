#pragma once
#include "levelset/bundle.h"
#include "run/indentation.h"
#include "run/response.h"
#include "run/scene.h"

#include <string>

namespace tessera {

/// Writes a run's results into `directory` (docs/outputs.md): results.h5, curve.csv,
/// summary.json and paraview/ (blocks at every snapshot, slab.pvd). Each file is written to a
/// temporary name and renamed, so a file is either complete or absent.
struct RunProvenance {
  std::string sceneText;    ///< the scene the run read (with a preset's or override's keys), kept in results.h5
  std::string stateDigest;  ///< of the World's state as written (state_digest.h), in summary.json and results.h5
};
void writeRunOutputs(const std::string& directory, const Scene& scene, const Bundle& bundle,
                     const ContactParameters& contact, const IndentationRecord& record,
                     const ResponseParameters& response, const RunProvenance& provenance);

/// The table of a sweep as HDF5: `keys` (K strings), `values` (C x K: each case's swept values),
/// `columns` (names) and `table` (C x columns, numbers), `case`, `failure_mode`, `stop_reason` (C strings).
void writeSweepTable(const std::string& path, const std::vector<std::string>& keys,
                     const std::vector<std::vector<double>>& values, const std::vector<std::string>& columns,
                     const std::vector<std::vector<double>>& table, const std::vector<std::string>& cases,
                     const std::vector<std::string>& failureModes, const std::vector<std::string>& stopReasons);

}  // namespace tessera

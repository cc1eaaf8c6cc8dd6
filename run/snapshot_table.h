#pragma once
#include "run/indentation.h"

#include <hdf5.h>

#include <string>
#include <vector>

namespace tessera {

/// The snapshots of a record (poses, velocities, the indenter, the contact records) as datasets
/// with units in `group` (docs/outputs.md, results.h5 "snapshots/"): the one layout of results.h5
/// and checkpoint.h5, as curve_table.h is for the curve. `bodyNames` in bundle order.
void writeSnapshots(hid_t group, const std::vector<Snapshot>& snapshots, const std::vector<std::string>& bodyNames);
/// Reads what writeSnapshots wrote for `bodies` bodies; std::runtime_error when a size, count or
/// index does not match.
std::vector<Snapshot> readSnapshots(hid_t group, std::size_t bodies);

/// The bodies out at the end (results.h5 "fallen/": names, delta, retired, touching).
void writeFallen(hid_t group, const std::vector<FallenBody>& fallen);
std::vector<FallenBody> readFallen(hid_t group);

}  // namespace tessera

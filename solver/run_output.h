#pragma once
#include "levelset/bundle.h"
#include "solver/indentation.h"
#include "solver/response.h"
#include "solver/scene.h"

#include <string>

namespace tessera {

/// Writes a run's results into `directory` (docs/outputs.md): results.h5, curve.csv,
/// summary.json and paraview/ (blocks at every snapshot, slab.pvd). Each file is written to a
/// temporary name and renamed, so a file is either complete or absent.
void writeRunOutputs(const std::string& directory, const Scene& scene, const Bundle& bundle,
                     const ContactParameters& contact, const IndentationRecord& record,
                     const ResponseParameters& response);

}  // namespace tessera

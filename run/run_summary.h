#pragma once
#include "run/indentation.h"
#include "run/response.h"
#include "run/run_output.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace tessera {

/// One shape as summary.json lists it.
struct SummaryShape {
  std::string name;
  std::string levelSet;        ///< which level set the run used (levelSetPath)
  double voxel = 0;            ///< m
  double nodeSpacing = 0;      ///< m
  double edgeNodeSpacing = 0;  ///< m
  long nodes = 0;
};

/// The material and contact model as summary.json records them.
struct SummaryMaterial {
  double youngsModulus = 0;        ///< Pa
  double friction = 0;
  double normalStiffness = 0;      ///< N/m^3, k_n
  double tangentialStiffness = 0;  ///< N/m^3, k_t
  double indenterStiffnessFactor = 1;
  double indenterRadius = 0;       ///< m
  double indenterSpeed = 0;        ///< m/s
  double spanLength = 0;           ///< m
  long spanInterfaces = 0;
  std::string contactEvaluation, contactArea, stiffnessRule;  ///< the scene's names
};

/// How the run went, as summary.json's "run" records it.
struct SummaryRun {
  std::string method;  ///< "explicit" or "implicit"
  double timeStep = 0;  ///< s
  long steps = 0, newtonIterations = 0, cutbacks = 0, dynamicIncrements = 0;
  double settleTime = 0;  ///< s
  long settleSteps = 0;
  bool settled = false;
  double settleKinetic = 0, settleMaxTime = 0;  ///< J, s
  long sunkWhileSettling = 0;
  double wallSeconds = 0;
  long samples = 0, snapshots = 0;
};

/// summary.json (docs/outputs.md), in SI units: its one definition. The run writes it
/// (writeRunOutputs); the sweep reads it back for its completeness rule and its tables, a resumed
/// run for how it stopped, and Python's Simulation.response is its "response" part in SI units.
/// Each field is named once, with its unit (runSummaryJson): the file's key is the name and unit
/// ("peak_load_N", "delta_at_peak_mm"), its value in that unit.
struct RunSummary {
  std::string generator, scene, bundle, target;
  StopReason stopReason = StopReason::Running;
  std::string stateDigest;
  ResponseParameters response;
  std::vector<FallenBody> fallen;
  double failureLoadFraction = 0, quasiStaticTarget = 0;
  double deltaMax = 0;  ///< m
  SummaryMaterial material;
  std::vector<SummaryShape> shapes;
  SummaryRun run;
};

RunSummary makeRunSummary(const Scene& scene, const Bundle& bundle, const ContactParameters& contact,
                          const IndentationRecord& record, const ResponseParameters& response,
                          const RunProvenance& provenance);

/// The summary as JSON: the file's keys and units (withUnits), or plain names in SI units (Python).
nlohmann::json runSummaryJson(const RunSummary& summary, bool withUnits = true);
/// A summary.json's text read back. Throws InputError naming the key that is missing or of the
/// wrong type (or the JSON's own error).
RunSummary parseRunSummary(const std::string& text);
/// summary.json in `folder`, read back (InputError naming the file).
RunSummary readRunSummary(const std::filesystem::path& folder);

}  // namespace tessera

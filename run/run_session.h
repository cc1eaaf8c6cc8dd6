#pragma once
#include "levelset/bundle.h"
#include "run/checkpoint.h"
#include "run/indentation.h"
#include "run/response.h"
#include "run/scene.h"
#include "solver/world.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tessera {

class FolderLock;

/// A new run of one scene (what `tessera run SCENE` and `tessera.Simulation` are given).
struct RunRequest {
  std::string scene;   ///< scene file (TOML, docs/scene.md)
  std::vector<std::pair<std::string, double>> overrides;  ///< "table.key" -> value (SI) over the scene's
  std::string preset;  ///< a named preset over the scene (presets.h), "" for none
  std::string bundle;  ///< bundle directory instead of the scene's, "" to keep it
  int threads = -1;    ///< threads of the contact loop; -1: the scene's, 0: all cores
  /// Run folder for the results and checkpoints; "" for none (the run lives in memory only).
  std::string output;
};

/// Lines for the user while a run is prepared ("note: ...", "warning: ..."), without a prefix.
using RunLog = std::function<void(const std::string&)>;

/// Contact parameters with the span (M, L) of k_n = E M / L resolved: the scene's [span] if it
/// sets one, else the bundle's. InputError naming `scenePath` when neither defines it.
ContactParameters resolveSpan(const ContactParameters& scene, const Bundle& bundle, const std::string& scenePath);

/// The bundle of a scene, ready to run: read and checked (bodies present, the load point valid),
/// its shapes re-prepared at the scene's [resolution] if it sets one (the body frames, and so
/// every pose, unchanged), and refused if bodies overlap (as tile and assemble refuse).
Bundle loadRunBundle(const Scene& scene, const RunLog& log);

/// One indentation test made ready to run or resume: the scene, the bundle, the World, the
/// protocol's state and the record, and the run folder it writes to (if any). Everything a
/// front end (the CLI, Python) does is: make one, set hooks, run(), read the results.
class RunSession {
public:
  /// A new run. With an output folder: the folder is checked writable and must not hold a run
  /// (InputError naming the fix), and is locked for the life of the session.
  static std::unique_ptr<RunSession> start(const RunRequest& request, const RunLog& log);
  /// The stopped run in `folder`, from its checkpoint, exactly as it started: refused, naming
  /// what changed, if its scene file, bundle or preset changed since. `bundle`: where the bundle
  /// is now if it moved ("" to find it); `preset`: must be the one it started with ("" any);
  /// `threads`: -1 the run's own count (bit-identical), else another.
  static std::unique_ptr<RunSession> resume(const std::string& folder, const std::string& bundle,
                                            const std::string& preset, int threads, const RunLog& log);
  ~RunSession();
  RunSession(const RunSession&) = delete;
  RunSession& operator=(const RunSession&) = delete;

  /// Runs (or continues) the test to its stop. With a run folder, the checkpoint and the result
  /// files are written every scene.output.checkpointSeconds and at the stop (hooks.checkpoint is
  /// the session's own then; any given is called after it). A SolverInstability is rethrown
  /// after the results recorded so far are written.
  void run(RunHooks hooks);

  /// Writes the result files into the run folder (nothing without one).
  void writeOutputs() const;
  /// A resumed run that had finished and whose result files were all written at its stop (its
  /// summary.json, written last, says how it stopped): there is nothing to resume or rewrite.
  bool finishedAndWritten() const;
  ResponseParameters response() const;

  const Scene& scene() const { return scene_; }
  const Bundle& bundle() const { return bundle_; }
  const ContactParameters& contact() const { return contact_; }
  World& world() { return *world_; }
  const World& world() const { return *world_; }
  const IndentationRecord& record() const { return record_; }
  const IndentationState& state() const { return state_; }
  const std::string& output() const { return output_; }
  const CheckpointSource& source() const { return source_; }
  bool resumed() const { return resumed_; }

private:
  RunSession() = default;
  void prepare(const RunLog& log);

  Scene scene_;
  CheckpointSource source_;
  Bundle bundle_;
  ContactParameters contact_;
  std::unique_ptr<World> world_;
  IndentationRecord record_;
  IndentationState state_;
  std::string output_;
  /// A scene changed by a preset or overrides is written beside the results (OUT/scene.toml) only
  /// once they are: until then its messages name the file the user wrote, and what changed it.
  std::string messageName_;
  void namedForUser(const std::string& path, const std::function<void()>& work) const;
  std::unique_ptr<FolderLock> lock_;
  bool resumed_ = false;
};

}  // namespace tessera

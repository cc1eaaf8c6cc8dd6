#include "run/run_session.h"

#include "run/geometry_bundle.h"

#include "io/file_digest.h"
#include "io/folder_lock.h"
#include "io/input_error.h"
#include "io/output_directory.h"
#include "io/safe_write.h"
#include "levelset/assembly_checks.h"
#include "levelset/shape_builder.h"
#include "run/load_point.h"
#include "run/presets.h"
#include "run/protocol_scale.h"
#include "run/run_output.h"
#include "run/run_summary.h"
#include "run/state_digest.h"

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iterator>
#include <sstream>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// threads: -1 the scene's, 0 all cores, else a count up to kMaxThreads.
void checkThreadRequest(int threads) {
  if (threads < -1 || threads > kMaxThreads)
    throw InputError("threads must be 0 (all cores) or 1 to " + std::to_string(kMaxThreads) + ", got " + std::to_string(threads));
}

std::string bundleFile(const std::string& bundle) {
  return fs::is_directory(bundle) ? (fs::path(bundle) / kBundleFileName).string() : bundle;
}

std::string checkpointFile(const std::string& folder) { return (fs::path(folder) / "checkpoint.h5").string(); }

// The scene a run reads is the file's text unless a preset or overrides changed it; then it is
// kept beside the results as OUT/scene.toml (and named so in messages).
bool derivedScene(const CheckpointSource& source) { return textDigest(source.sceneText) != source.sceneDigest; }

std::string keptScenePath(const std::string& output) { return (fs::path(output) / "scene.toml").string(); }

// Lengths and a speed given in SI units, against the slab they are for: an indenter radius or a
// delta_max outside the range their ratios allow (1e-3 to 100 times the loaded block's thickness
// h, as the bundle places it), or an indenter speed that moves it more than a tenth of the
// broad-phase margin a time step (its contacts would be found late; the cap a sample hook's
// steering has), is almost always a value in mm or mm/s. Refused before a run starts, naming the
// value and the fix (a resumed run keeps what it started with).
void checkValuesAgainstSlab(const Scene& scene, const Bundle& bundle, const World& world) {
  const LoadPoint load = chooseLoadPoint(bundle, scene.indenter);
  const Body& loaded = bundle.bodies[load.body];
  const double h = loadedThickness(bundle.shapes[loaded.shape].mesh, loaded.orientation, loaded.position,
                                   loaded.position.head<2>() + load.offset);
  const auto length = [&](const std::string& key, double value, const std::string& ratioKey) {
    if (value <= 0 || (value >= 1e-3 * h && value <= 100 * h)) return;
    std::ostringstream m;
    m << scene.path << ": " << key << " = " << value << " m is " << std::setprecision(3) << value / h
      << " x the loaded block's thickness h = " << std::setprecision(4) << h * 1e3 << " mm (the range is 0.001 to 100 h); ";
    if (value > 100 * h) m << "lengths are in m (" << value << " mm is " << value * 1e-3 << " m), or ";
    m << "set it to 0 for " << ratioKey << " x h";
    throw InputError(m.str());
  };
  length("indenter.radius", scene.indenter.radius, "indenter.radius_ratio");
  length("protocol.delta_max", scene.protocol.deltaMax, "protocol.delta_max_ratio");
  const double speed = scene.indenter.speed, margin = world.settings().broadPhaseMargin, fastest = 0.1 * margin / world.timeStep();
  if (speed > fastest && world.settings().method == SolverMethod::Explicit) {  // implicit increments follow any speed
    std::ostringstream m;
    m << std::setprecision(3) << scene.path << ": indenter.speed = " << speed << " m/s moves the indenter "
      << speed * world.timeStep() * 1e6 << " um a time step, more than a tenth of the broad-phase margin (" << margin * 1e6
      << " um), so its contacts would be found late; speeds are in m/s (" << speed << " mm/s is " << speed * 1e-3
      << " m/s), at most " << fastest << " m/s here, or set it to 0 for the automatic speed";
    throw InputError(m.str());
  }
  // A run that cannot end: loading or settling that takes more than 10^9 time steps (hours on the
  // smallest slab, weeks on a large one) is a value in the wrong unit, never a test.
  constexpr double kMostSteps = 1e9;
  const double dt = world.timeStep(), deltaMax = scene.protocol.deltaMax > 0 ? scene.protocol.deltaMax : scene.protocol.deltaMaxRatio * h;
  const double v = indenterSpeed(world, scene.indenter, h), settle = settleTimeLimit(world, scene.protocol);
  if (!(deltaMax / (v * dt) <= kMostSteps)) {
    std::ostringstream m;
    m << std::setprecision(3) << scene.path << ": an indenter speed of " << v << " m/s takes " << deltaMax / (v * dt)
      << " time steps of " << dt << " s to reach delta_max = " << deltaMax * 1e3 << " mm, more than 1e9; speeds are in m/s "
      << "(indenter.speed, or indenter.speed_ratio of the automatic speed), at least " << deltaMax / (kMostSteps * dt)
      << " m/s here";
    throw InputError(m.str());
  }
  if (!(settle / dt <= kMostSteps)) {
    std::ostringstream m;
    m << std::setprecision(3) << scene.path << ": settling for up to " << settle << " s takes " << settle / dt
      << " time steps of " << dt << " s, more than 1e9; lower protocol.settle_max_time (s) or settle_max_time_ratio";
    throw InputError(m.str());
  }
}

}  // namespace

ContactParameters resolveSpan(const ContactParameters& scene, const Bundle& bundle, const std::string& scenePath) {
  ContactParameters contact = scene;
  if (contact.spanLength == 0) contact.spanLength = bundle.spanLength;
  if (contact.spanInterfaces == 0) contact.spanInterfaces = bundle.spanInterfaces;
  if (!(contact.spanLength > 0) || contact.spanInterfaces < 1)
    throw InputError(scenePath + ": the span (M, L) for k_n = E M / L is unknown: the bundle does not define one; "
                     "set [span] length and interfaces");
  return contact;
}

Bundle loadRunBundle(const Scene& scene, const RunLog& log) {
  Bundle bundle = readBundle(scene.bundle);
  if (bundle.bodies.empty())
    throw InputError(scene.bundle + ": the bundle holds no bodies; build a slab with tessera tile");
  try {
    chooseLoadPoint(bundle, scene.indenter);  // where it will load: checked before any work
  } catch (const std::invalid_argument& e) {
    throw InputError(scene.path + ": " + e.what());
  }
  if (scene.resolution.any()) {
    // Each shape again from its (body-frame) mesh: the body frame, and so every pose, is unchanged.
    const ResolutionOverride& o = scene.resolution;
    for (Shape& shape : bundle.shapes) {
      ShapeResolution r = shape.resolution;
      if (o.nodeSpacing > 0 || o.nodeSpacingRatio > 0) {
        r.nodeSpacing = o.nodeSpacing;
        r.nodeSpacingRatio = o.nodeSpacingRatio;
      }
      if (o.edgeSpacingFraction > 0) r.edgeSpacingFraction = o.edgeSpacingFraction;
      if (o.sizeGradient > 0) r.sizeGradient = o.sizeGradient;
      if (o.voxelSize > 0 || o.voxelRatio > 0) {
        r.voxelSize = o.voxelSize;
        r.voxelRatio = o.voxelRatio;
      }
      PrepLog prep;
      ShapeLimits limits;
      limits.anySize = true;  // the bundle's shapes were accepted when they were prepared
      shape = buildShape(shape.name, shape.mesh, shape.source, r, scene.path, prep, limits);
      if (log)
        for (const auto& w : prep.warnings) log("warning: shape '" + shape.name + "': " + w);
    }
    if (log) {
      char line[160];
      const ShapeResolution& r = bundle.shapes[0].resolution;
      std::snprintf(line, sizeof line, "shapes re-prepared at node spacing %.4g mm (%.4g mm at sharp edges), voxel %.4g mm",
                    r.nodeSpacing * 1e3, r.edgeSpacingFraction * r.nodeSpacing * 1e3, r.voxelSize * 1e3);
      log(line);
    }
  }
  for (Shape& shape : bundle.shapes)  // the exact mesh level sets of the shapes that will use them
    if (scene.solver.exactMeshLevelSets && !(shape.convex && scene.solver.exactConvexLevelSets)) deriveExactMesh(shape);
  // The bodies as the bundle places them may not overlap (a bundle edited by hand, or two bodies
  // placed on one another): the same check as tile and assemble (reading the exact meshes just
  // derived), before any work.
  const double tolerance = 0.1 * finestVoxel(bundle);
  refuseOverlaps(bundle, checkAssembly(bundle, tolerance, 0.5 * finestVoxel(bundle)), tolerance, scene.bundle + ": ",
                 "rebuild the bundle with tessera tile or assemble");
  return bundle;
}

std::unique_ptr<RunSession> RunSession::start(const RunRequest& request, const RunLog& log) {
  std::unique_ptr<RunSession> session(new RunSession());
  RunSession& s = *session;
  s.output_ = request.output;
  checkThreadRequest(request.threads);
  if (!s.output_.empty() && fs::exists(checkpointFile(s.output_)))
    throw InputError(s.output_ + ": holds a run already; resume it with --resume " + s.output_ + " or choose another -o");
  const std::string sceneText = readSceneFile(request.scene);
  std::vector<std::pair<std::string, double>> overrides;
  if (!request.preset.empty()) overrides = findPreset(request.preset).overrides;
  overrides.insert(overrides.end(), request.overrides.begin(), request.overrides.end());
  CheckpointSource& source = s.source_;
  if (!overrides.empty()) {
    // The scene with the preset's keys (and the caller's), kept as OUT/scene.toml with the results.
    std::string origin = request.scene;
    if (!request.preset.empty()) origin += " with --preset " + request.preset;
    if (!request.overrides.empty()) origin += " with " + std::to_string(request.overrides.size()) + " override(s)";
    if (!request.bundle.empty())
      origin += "\n# run on the bundle " + fs::absolute(request.bundle).lexically_normal().string() + " (in place of the one below)";
    source.sceneText = "# " + origin + "\n" + sceneWithOverrides(request.scene, overrides);
    s.messageName_ = request.scene + " (with " + (request.preset.empty() ? "overrides" : "--preset " + request.preset) + ")";
    const std::string kept = s.output_.empty() ? request.scene : keptScenePath(s.output_);
    s.namedForUser(kept, [&] { s.scene_ = readSceneText(source.sceneText, kept); });
  } else {
    source.sceneText = sceneText;
    s.scene_ = readSceneText(sceneText, request.scene);
  }
  if (!request.bundle.empty()) s.scene_.bundle = request.bundle;
  if (s.scene_.bundle.empty()) s.scene_.bundle = geometryBundle(*s.scene_.geometry, s.output_.empty() ? "" : geometryCache(s.output_), log);
  if (request.threads >= 0) s.scene_.solver.threads = request.threads;
  if (!s.output_.empty()) {
    // Where the results go, checked before any work: writable, and not the bundle itself.
    if (fs::exists(s.output_) && fs::exists(s.scene_.bundle) && fs::equivalent(s.output_, s.scene_.bundle))
      throw InputError(s.output_ + ": is the bundle's folder; write the results to another -o");
    requireWritableDirectory(s.output_);
  }
  source.scene = fs::absolute(request.scene).lexically_normal().string();
  source.sceneDigest = textDigest(sceneText);
  source.preset = request.preset;
  source.bundle = fs::absolute(s.scene_.bundle).lexically_normal().string();
  source.bundleRelative = s.output_.empty() ? std::string()
                                            : fs::path(source.bundle).lexically_relative(fs::absolute(s.output_).lexically_normal()).string();
  source.bundleDigest = fs::exists(bundleFile(s.scene_.bundle)) ? fileDigest(bundleFile(s.scene_.bundle)) : "";
  source.threads = s.scene_.solver.threads;
  s.namedForUser(s.scene_.path, [&] {
    s.prepare(log);
    checkValuesAgainstSlab(s.scene_, s.bundle_, *s.world_);
  });
  if (!s.output_.empty()) {
    s.lock_ = std::make_unique<FolderLock>(s.output_, "a run");  // after every check: a refused run leaves no folder
    if (fs::exists(checkpointFile(s.output_)))
      throw InputError(s.output_ + ": another run started there meanwhile; choose another -o");
    // What an earlier run that stopped before its first checkpoint left (its kept scene, its
    // ParaView frames, written once each) is not this run's.
    fs::remove(keptScenePath(s.output_));
    fs::remove_all(fs::path(s.output_) / "paraview");
  }
  return session;
}

std::unique_ptr<RunSession> RunSession::resume(const std::string& folder, const std::string& bundle,
                                               const std::string& preset, int threads, const RunLog& log) {
  std::unique_ptr<RunSession> session(new RunSession());
  RunSession& s = *session;
  s.output_ = folder;
  s.resumed_ = true;
  checkThreadRequest(threads);
  if (!fs::is_directory(folder)) throw InputError(folder + ": no such run folder to resume");
  s.lock_ = std::make_unique<FolderLock>(folder, "a run");
  s.source_ = readCheckpointSource(checkpointFile(folder));
  const CheckpointSource& source = s.source_;

  // The scene exactly as it started: its text from the checkpoint; the scene file, bundle and
  // preset compared with what it started with.
  const std::string newRun = "start a new run with -o NEW for new values";
  const std::string fix = "a resumed run continues with exactly what it started with; " + newRun;
  if (!preset.empty() && preset != source.preset)
    throw InputError(folder + ": this run started " + (source.preset.empty() ? "without --preset" : "with --preset " + source.preset) +
                     ", not --preset " + preset + "; " + fix);
  if (fs::is_regular_file(source.scene) && textDigest(readSceneFile(source.scene)) != source.sceneDigest)
    throw InputError(source.scene + ": changed since the run in " + folder + " started; restore it to resume, or " + newRun);
  const std::string kept = keptScenePath(folder);
  const bool derived = derivedScene(source);
  if (derived && fs::exists(kept) && readSceneFile(kept) != source.sceneText)
    throw InputError(kept + ": changed since the run started; restore it to resume, or " + newRun);
  s.scene_ = readSceneText(source.sceneText, derived ? kept : source.scene);
  const fs::path beside = fs::path(folder) / source.bundleRelative;
  s.scene_.bundle = !bundle.empty() ? bundle : fs::exists(bundleFile(beside.string())) ? beside.string() : source.bundle;
  if (!fs::exists(bundleFile(s.scene_.bundle)))
    throw InputError(folder + ": the bundle of this run is gone from " + source.bundle + "; give where it is now with --bundle DIR");
  if (fileDigest(bundleFile(s.scene_.bundle)) != source.bundleDigest)
    throw InputError(s.scene_.bundle + ": not the bundle the run in " + folder + " started with (re-tiled or edited since); " + fix);
  s.scene_.solver.threads = source.threads;
  if (threads >= 0 && threads != source.threads) {
    if (log) log("note: resuming with " + std::to_string(threads) + " threads instead of " + std::to_string(source.threads));
    s.scene_.solver.threads = threads;
  }
  s.prepare(log);

  WorldState restored = s.world_->state();
  readCheckpoint(checkpointFile(folder), restored, s.state_, s.record_);
  try {
    s.world_->restore(restored);
  } catch (const std::invalid_argument& e) {
    throw InputError(checkpointFile(folder) + ": corrupt checkpoint (" + e.what() + "); " + kUnreadableCheckpointFix);
  }
  return session;
}

RunSession::~RunSession() = default;

void RunSession::namedForUser(const std::string& path, const std::function<void()>& work) const {
  try {
    work();
  } catch (const InputError& e) {
    const std::string message = e.what(), named = path + ": ";
    if (messageName_.empty() || message.rfind(named, 0) != 0) throw;
    throw InputError(messageName_ + ": " + message.substr(named.size()));
  }
}

void RunSession::prepare(const RunLog& log) {
  bundle_ = loadRunBundle(scene_, log);
  contact_ = resolveSpan(scene_.contact, bundle_, scene_.path);
  // The World checks what only the bundle and material decide (e.g. a fixed time step against
  // the stability estimate): a bad scene value, reported as such.
  try {
    world_ = std::make_unique<World>(bundle_.shapes, bundle_.bodies, contact_, scene_.solver);
  } catch (const std::invalid_argument& e) {
    throw InputError(scene_.path + ": " + e.what());
  }
}

ResponseParameters RunSession::response() const {
  int freeBodies = 0;
  for (const Body& b : bundle_.bodies) freeBodies += b.fixed ? 0 : 1;
  const ResponseSettings analysis{contact_.youngsModulus, contact_.spanLength, scene_.protocol.failureLoadFraction, freeBodies,
                                  scene_.protocol.stiffnessFitRatio, scene_.protocol.quasiStaticLimit};
  return analyseResponse(record_, analysis);
}

void RunSession::writeOutputs() const {
  if (output_.empty()) return;
  // A scene changed by a preset or overrides is kept beside its results (its name in them).
  if (derivedScene(source_) && !fs::exists(scene_.path)) writeTextFileSafely(scene_.path, source_.sceneText);
  writeRunOutputs(output_, scene_, bundle_, contact_, record_, response(), {source_.sceneText, stateDigest(*world_)});
}

bool RunSession::finishedAndWritten() const {
  if (!resumed_ || !record_.finished()) return false;
  try {
    return readRunSummary(output_).stopReason == record_.stopReason;
  } catch (const InputError&) {
    return false;  // missing or unreadable: written again by the resumed run
  }
}

void RunSession::run(RunHooks hooks) {
  if (!output_.empty()) {
    hooks.checkpointSeconds = scene_.output.checkpointSeconds;
    const auto callerCheckpoint = hooks.checkpoint;
    hooks.checkpoint = [this, callerCheckpoint](const IndentationState& s) {
      writeCheckpoint(checkpointFile(output_), source_, world_->state(), s, record_);
      writeOutputs();
      if (callerCheckpoint) callerCheckpoint(s);
    };
  }
  if (!hooks.interrupted) hooks.interrupted = [] { return false; };
  try {
    runIndentation(*world_, bundle_, scene_, record_, state_, hooks);
  } catch (const SolverInstability&) {
    record_.stopReason = StopReason::Instability;
    recordStepping(record_, *world_);
    writeOutputs();  // what was recorded, not the unstable state
    throw;
  }
}

}  // namespace tessera

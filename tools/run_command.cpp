// tessera run: the indentation test of a slab, end to end.
#include "geometry/file_digest.h"
#include "geometry/input_error.h"
#include "geometry/safe_write.h"
#include "levelset/assembly.h"
#include "levelset/bundle.h"
#include "levelset/shape_builder.h"
#include "solver/checkpoint.h"
#include "solver/indentation.h"
#include "solver/load_point.h"
#include "solver/presets.h"
#include "solver/response.h"
#include "solver/run_output.h"
#include "solver/scene.h"
#include "solver/world.h"
#include "tools/assembly_checks.h"
#include "tools/commands.h"
#include "tools/folder_lock.h"
#include "tools/output_directory.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>

#include <unistd.h>

namespace tessera::tools {

namespace fs = std::filesystem;

namespace {

std::atomic<bool> stopRequested{false};
extern "C" void requestStop(int) { stopRequested = true; }

struct RunArguments {
  std::string scene;
  std::string output;
  std::string resume;  // output directory of a stopped run
  std::string bundle;  // overrides the scene's
  std::string preset;  // named speed/accuracy setting over the scene
  int threads = -1;
  bool noPlot = false;
};

// Runs Debian's Python on a plotting script of tools/plot; a failure only costs the picture, and
// the script's own one-line reason is shown.
void drawPicture(const std::string& script, const fs::path& out, const std::string& picture) {
  const fs::path path = fs::path(TESSERA_SOURCE_DIR) / "tools" / "plot" / script;
  const fs::path log = out / (".plot-" + picture + ".log");
  const std::string command = "/usr/bin/python3 '" + path.string() + "' '" + out.string() + "' >'" + log.string() + "' 2>&1";
  if (!fs::exists(path)) {
    std::cerr << "run: note: " << picture << " not drawn (" << path.string() << " is missing)\n";
  } else if (std::system(command.c_str()) != 0) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    std::cerr << "run: note: " << picture << " not drawn (" << (last.empty() ? "the plotting script failed" : last) << ")\n";
  }
  std::error_code ignored;
  fs::remove(log, ignored);
}

void printSummary(const IndentationRecord& record, const ResponseParameters& r, double failureFraction, const std::string& out) {
  std::printf("settled in %.4g s (%ld steps)%s; loaded block '%s'; stopped: %s\n", record.settleTime, record.settleSteps,
              record.settled ? "" : " (not settled)", record.targetName.c_str(), record.stopReason.c_str());
  std::printf("  peak load          P_max = %.4g N at delta = %.4g mm\n", r.peakLoad, r.deltaAtPeak * 1e3);
  std::printf("  initial stiffness  K = %.4g N/mm (fit over delta in [%.3g, %.3g] mm)\n", r.stiffness * 1e-3,
              r.fitFrom * 1e3, r.fitTo * 1e3);
  if (r.failureDeflection >= 0)
    std::printf("  failure deflection %.4g mm (load below %.3g x P_max; loaded block moved %.4g mm = %.3g h)\n",
                r.failureDeflection * 1e3, failureFraction,
                r.atFailure.blockDisplacement * 1e3, r.thickness > 0 ? r.atFailure.blockDisplacement / r.thickness : 0.0);
  else
    std::printf("  failure deflection none (the load stayed above the failure fraction of P_max)\n");
  std::printf("  loading energy     W = %.4g mJ to failure, %.4g mJ to the end (delta %.4g mm)\n", r.energy * 1e3,
              r.energyToEnd * 1e3, r.end.delta * 1e3);
  std::printf("  failure            %s", r.failureMode.c_str());
  for (const FallenBody& f : record.fallen)
    std::printf(" [%s out at %.3g mm%s]", f.name.c_str(), f.delta * 1e3,
                f.retired ? ", retired" : f.touching ? ", pushed through, still touching" : "");
  std::printf("\n  load drops         %zu after the peak", r.drops.size());
  for (const LoadDrop& d : r.drops) std::printf(" [%.3g mm: %.4g -> %.4g N]", d.delta * 1e3, d.before, d.after);
  const CurveSample& e = r.end;
  std::printf("\n  energy (mJ)        work %.4g + gravity %.3g = elastic %.4g + kinetic %.3g + friction %.4g + damping %.4g"
              " + retired %.3g + projection %.3g; residual %.3g (%.2g %% of the work)\n",
              e.externalWork * 1e3, e.gravityWork * 1e3, e.elastic * 1e3, e.kinetic * 1e3, e.friction * 1e3, e.damping * 1e3,
              e.retiredKinetic * 1e3, e.projection * 1e3, e.residual * 1e3,
              e.externalWork > 0 ? 100 * std::abs(e.residual) / e.externalWork : 0.0);
  std::printf("  quasi-static check max KE / W before the peak = %.2e%s\n", r.quasiStaticRatio,
              r.quasiStatic ? "" : " (above the limit: loading too fast, lower indenter.speed)");
  std::printf("  indenter           radius %.4g mm at %.4g mm/s; h = %.4g mm\n", record.indenterRadius * 1e3,
              record.indenterSpeed * 1e3, record.thickness * 1e3);
  std::printf("  %ld steps of %.3g s in %.1f s\n", record.steps, record.timeStep, record.wallSeconds);
  std::string files;
  for (const char* f : {"results.h5", "curve.csv", "summary.json", "curve.png", "snapshots.png", "paraview/slab.pvd", "checkpoint.h5"})
    if (fs::exists(fs::path(out) / f)) files += (files.empty() ? "" : ", ") + std::string(f);
  std::printf("written to %s (%s)\n", out.c_str(), files.c_str());
}

std::string readText(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError(path + ": no such scene file; see assets/scenes/default.toml for an example");
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string bundleFile(const std::string& bundle) {
  return fs::is_directory(bundle) ? (fs::path(bundle) / kBundleFileName).string() : bundle;
}

// The scene of a stopped run, exactly as it started: its text from the checkpoint, its bundle
// found beside the run folder as it was (folders moved together) or where it was. Refuses, naming
// what changed, a scene file edited since, another bundle, or another preset.
Scene resumedScene(const std::string& out, const CheckpointSource& source, const RunArguments& a) {
  const std::string newRun = "start a new run with -o NEW for new values";
  const std::string fix = "a resumed run continues with exactly what it started with; " + newRun;
  if (!a.preset.empty() && a.preset != source.preset)
    throw InputError(out + ": this run started " + (source.preset.empty() ? "without --preset" : "with --preset " + source.preset) +
                     ", not --preset " + a.preset + "; " + fix);
  if (fs::is_regular_file(source.scene) && textDigest(readText(source.scene)) != source.sceneDigest)
    throw InputError(source.scene + ": changed since the run in " + out + " started; restore it to resume, or " + newRun);
  const fs::path kept = fs::path(out) / "scene.toml";
  if (!source.preset.empty() && fs::exists(kept) && readText(kept.string()) != source.sceneText)
    throw InputError(kept.string() + ": changed since the run started; restore it to resume, or " + newRun);
  Scene scene = readSceneText(source.sceneText, source.preset.empty() ? source.scene : kept.string());
  const fs::path beside = fs::path(out) / source.bundleRelative;
  scene.bundle = !a.bundle.empty() ? a.bundle : fs::exists(bundleFile(beside.string())) ? beside.string() : source.bundle;
  if (!fs::exists(bundleFile(scene.bundle)))
    throw InputError(out + ": the bundle of this run is gone from " + source.bundle + "; give where it is now with --bundle DIR");
  if (fileDigest(bundleFile(scene.bundle)) != source.bundleDigest)
    throw InputError(scene.bundle + ": not the bundle the run in " + out + " started with (re-tiled or edited since); " + fix);
  scene.solver.threads = source.threads;
  return scene;
}

int runTest(const RunArguments& a) {
  const bool resume = !a.resume.empty();
  if (resume == !a.scene.empty())
    throw InputError("give either a SCENE file (with -o OUTDIR) or --resume OUTDIR");
  const std::string out = resume ? a.resume : a.output;
  if (!resume && out.empty()) throw InputError("-o OUTDIR is required with a scene");
  const std::string checkpointFile = (fs::path(out) / "checkpoint.h5").string();
  if (a.threads < -1) throw InputError("--threads must be 0 (all cores) or a positive number, got " + std::to_string(a.threads));

  Scene scene;
  CheckpointSource source;
  std::optional<FolderLock> lock;  // one writer per run folder, held to the end
  if (resume) {
    if (!fs::is_directory(out)) throw InputError(out + ": no such run folder to resume");
    lock.emplace(out, "a run");
    source = readCheckpointSource(checkpointFile);
    scene = resumedScene(out, source, a);
    if (a.threads >= 0 && a.threads != source.threads) {
      std::cerr << "run: note: resuming with " << a.threads << " threads instead of " << source.threads << "\n";
      scene.solver.threads = a.threads;
    }
  } else {
    if (fs::exists(checkpointFile))
      throw InputError(out + ": holds a run already; resume it with --resume " + out + " or choose another -o");
    const std::string sceneText = readText(a.scene);
    if (!a.preset.empty()) {
      // The scene with the preset's keys, kept as OUT/scene.toml with the first results.
      source.sceneText = "# " + a.scene + " with --preset " + a.preset + "\n" +
                         sceneWithOverrides(a.scene, findPreset(a.preset).overrides);
      scene = readSceneText(source.sceneText, (fs::path(out) / "scene.toml").string());
    } else {
      source.sceneText = sceneText;
      scene = readSceneText(sceneText, a.scene);
    }
    if (!a.bundle.empty()) scene.bundle = a.bundle;
    if (a.threads >= 0) scene.solver.threads = a.threads;
    // Where the results go, checked before any work: writable, and not the bundle itself.
    if (fs::exists(out) && fs::exists(scene.bundle) && fs::equivalent(out, scene.bundle))
      throw InputError(out + ": is the bundle's folder; write the results to another -o");
    requireWritableDirectory(out);
    source.scene = fs::absolute(a.scene).lexically_normal().string();
    source.sceneDigest = textDigest(sceneText);
    source.preset = a.preset;
    source.bundle = fs::absolute(scene.bundle).lexically_normal().string();
    source.bundleRelative = fs::path(source.bundle).lexically_relative(fs::absolute(out).lexically_normal()).string();
    source.bundleDigest = fs::exists(bundleFile(scene.bundle)) ? fileDigest(bundleFile(scene.bundle)) : "";
    source.threads = scene.solver.threads;
  }
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
      if (o.voxelSize > 0 || o.voxelRatio > 0) {
        r.voxelSize = o.voxelSize;
        r.voxelRatio = o.voxelRatio;
      }
      PrepLog log;
      ShapeLimits limits;
      limits.anySize = true;  // the bundle's shapes were accepted when they were prepared
      shape = buildShape(shape.name, shape.mesh, shape.source, r, scene.path, log, limits);
      for (const auto& w : log.warnings) std::cerr << "run: warning: shape '" << shape.name << "': " << w << "\n";
    }
    std::fprintf(stderr, "run: shapes re-prepared at node spacing %.4g mm, voxel %.4g mm\n",
                 bundle.shapes[0].resolution.nodeSpacing * 1e3, bundle.shapes[0].resolution.voxelSize * 1e3);
  }

  // The bodies as the bundle places them may not overlap (a bundle edited by hand, or two bodies
  // placed on one another): the same check as tile and assemble, before any work.
  {
    const double tolerance = 0.1 * finestVoxel(bundle);
    refuseOverlaps(bundle, checkAssembly(bundle, tolerance, 0.5 * finestVoxel(bundle)), tolerance, scene.bundle + ": ",
                   "rebuild the bundle with tessera tile or assemble");
  }
  ContactParameters contact = scene.contact;
  if (contact.spanLength == 0) contact.spanLength = bundle.spanLength;
  if (contact.spanInterfaces == 0) contact.spanInterfaces = bundle.spanInterfaces;
  if (!(contact.spanLength > 0) || contact.spanInterfaces < 1)
    throw InputError(scene.path + ": the span (M, L) for k_n = E M / L is unknown: the bundle does not define one; "
                     "set [span] length and interfaces");

  // The World checks what only the bundle and material decide (e.g. a fixed time step against
  // the stability estimate): a bad scene value, reported as such.
  const auto makeWorld = [&] {
    try {
      return World(bundle, contact, scene.solver);
    } catch (const std::invalid_argument& e) {
      throw InputError(scene.path + ": " + e.what());
    }
  };
  World world = makeWorld();
  IndentationRecord record;
  IndentationState state;
  if (!resume) {
    lock.emplace(out, "a run");  // made here, after every check: a refused run leaves no folder behind
    if (fs::exists(checkpointFile)) throw InputError(out + ": another run started there meanwhile; choose another -o");
  }
  if (resume) {
    WorldState restored = world.state();
    readCheckpoint(checkpointFile, restored, state, record);
    try {
      world.restore(restored);
    } catch (const std::invalid_argument& e) {
      throw InputError(checkpointFile + ": corrupt checkpoint (" + e.what() + "); start the run again from its scene");
    }
    std::fprintf(stderr, "run: resuming %s at t = %.6g s (step %ld)\n", out.c_str(), world.time(), world.stepCount());
  }
  std::fprintf(stderr, "run: %zu bodies, E = %.4g GPa, mu = %.3g, k_n = %.4g N/m^3, dt = %.3g s (automatic %.3g s)\n",
               bundle.bodies.size(), contact.youngsModulus * 1e-9, contact.friction, contact.normalStiffness(),
               world.timeStep(), world.automaticTimeStep());
  for (const Shape& shape : bundle.shapes)
    std::fprintf(stderr, "run: shape '%s': %s\n", shape.name.c_str(),
                 levelSetPath(shape, scene.solver.exactConvexLevelSets).c_str());

  int freeBodies = 0;
  for (const Body& b : bundle.bodies) freeBodies += b.fixed ? 0 : 1;
  const ResponseSettings analysis{contact.youngsModulus, contact.spanLength, scene.protocol.failureLoadFraction, freeBodies,
                                  scene.protocol.stiffnessFitRatio, scene.protocol.quasiStaticLimit};
  const auto response = [&] { return analyseResponse(record, analysis); };
  RunHooks hooks;
  hooks.progress = [](const Progress& p) {
    if (p.settling) {
      std::fprintf(stderr, "run: settling  KE %.3e J  step %9ld  %6.0f steps/s  ETA %.0f s + settling\n", p.kinetic, p.steps,
                   p.stepsPerSecond, p.etaSeconds);
      return;
    }
    std::fprintf(stderr, "run: delta %7.3f mm  P %9.3f N  KE/W %.2e  contacts %7ld  step %9ld  %6.0f steps/s  ETA %.0f s\n",
                 p.delta * 1e3, p.load, p.externalWork > 0 ? p.kinetic / p.externalWork : 0.0, p.contacts, p.steps,
                 p.stepsPerSecond, p.etaSeconds);
  };
  hooks.interrupted = [] { return stopRequested.load(); };
  hooks.warning = [](const std::string& w) { std::cerr << "run: warning: " << w << "\n"; };
  hooks.checkpointSeconds = scene.output.checkpointSeconds;
  const auto keepPresetScene = [&] {
    if (!source.preset.empty() && !fs::exists(scene.path)) writeTextFileSafely(scene.path, source.sceneText);
  };
  hooks.checkpoint = [&](const IndentationState& s) {
    keepPresetScene();
    writeCheckpoint(checkpointFile, source, world.state(), s, record);
    writeRunOutputs(out, scene, bundle, contact, record, response());
  };

  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  std::string failure;
  try {
    runIndentation(world, bundle, scene, record, state, hooks);
  } catch (const SolverInstability& e) {
    failure = e.what();
    record.stopReason = "instability";
    record.steps = world.stepCount();
    keepPresetScene();
    writeRunOutputs(out, scene, bundle, contact, record, response());  // what was recorded, not the unstable state
  }
  if (!record.settled && record.stopReason != "interrupted")
    std::fprintf(stderr, "run: warning: the slab had not settled after %.3g s (kinetic energy above %.3g J)\n",
                 record.settleTime, record.settleKinetic);
  if (!a.noPlot && !record.curve.empty()) {
    drawPicture("plot_curve.py", out, "curve.png");
    drawPicture("render_snapshots.py", out, "snapshots.png");
  }
  printSummary(record, response(), scene.protocol.failureLoadFraction, out);
  if (!failure.empty()) {
    std::cerr << "tessera: error: the run became unstable and was stopped: " << failure << "\n";
    return 3;
  }
  return record.stopReason == "interrupted" ? 130 : 0;
}

}  // namespace

void addRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArguments>();
  CLI::App* cmd = app.add_subcommand("run", "Run the indentation test of a slab: settle, indent, record P(delta), analyse.");
  cmd->add_option("scene", args->scene, "Scene file (TOML, docs/scene.md), e.g. assets/scenes/default.toml");
  cmd->add_option("-o,--output", args->output, "Directory for the results (created)");
  cmd->add_option("--resume", args->resume, "Continue the stopped run in this output directory from its checkpoint.h5");
  cmd->add_option("--bundle", args->bundle, "Bundle directory, instead of the scene's 'bundle'");
  std::string presetHelp = "Speed/accuracy setting over the scene's (docs/performance.md):";
  for (const Preset& p : presets()) presetHelp += "\n  " + p.name + ": " + p.description;
  cmd->add_option("--preset", args->preset, presetHelp);
  cmd->add_option("--threads", args->threads, "Threads for the contact loop [default: the scene's, 0 = all cores]");
  cmd->add_flag("--no-plot", args->noPlot, "Do not draw curve.png and snapshots.png");
  cmd->footer("Example: tessera run assets/scenes/default.toml --bundle out/default_slab -o out/run\n"
              "Ctrl-C stops the run and still writes everything recorded so far (exit status 130);\n"
              "tessera run --resume out/run continues it, exactly as if it had not stopped.");
  cmd->callback([args] {
    const int status = runTest(*args);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace tessera::tools

// tessera run: the indentation test of a slab, end to end.
#include "io/input_error.h"
#include "levelset/bundle.h"
#include "run/presets.h"
#include "run/run_session.h"
#include "tools/commands.h"
#include "tools/plot_scripts.h"

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

// Draws a picture with a plotting script (tools/plot); a failure only costs the picture, and the
// script's own one-line reason is shown.
void drawPicture(const std::string& script, const fs::path& out, const std::string& picture) {
  const fs::path log = out / (".plot-" + picture + ".log");
  std::error_code ignored;
  fs::remove(log, ignored);
  if (plotScript(script).empty()) {
    std::cerr << "run: note: " << picture << " not drawn (" << script << " is not installed beside tessera)\n";
  } else if (plotPython().empty()) {
    std::cerr << "run: note: " << picture << " not drawn (no python3; set TESSERA_PYTHON)\n";
  } else if (runPlotScript(script, {out.string()}, log.string()) != 0) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    std::cerr << "run: note: " << picture << " not drawn (" << (last.empty() ? "the plotting script failed" : last) << ")\n";
  }
  fs::remove(log, ignored);
}

// The result files in the run folder, as a list for the summary's last line.
std::string writtenFiles(const std::string& out) {
  std::string files;
  for (const char* f : {"results.h5", "curve.csv", "summary.json", "curve.png", "snapshots.png", "paraview/slab.pvd", "checkpoint.h5"})
    if (fs::exists(fs::path(out) / f)) files += (files.empty() ? "" : ", ") + std::string(f);
  return files;
}

// A run stopped while it settled has nothing to analyse: where the settling was, and how to go on.
void printSettlingSummary(const RunSession& session, const std::string& out) {
  const IndentationRecord& record = session.record();
  const World& world = session.world();
  std::printf("stopped: %s while settling, at %.4g s of up to %.4g s simulated (kinetic energy %.3e J; at rest below "
              "%.3e J); nothing loaded yet\n",
              stopReasonName(record.stopReason), world.time(), record.settleMaxTime, world.energy().kinetic, record.settleKinetic);
  std::printf("  %ld %s in %.1f s\n", record.steps, record.implicit ? "implicit increments" : "steps", record.wallSeconds);
  std::printf("written to %s (%s); go on with: tessera run --resume %s\n", out.c_str(), writtenFiles(out).c_str(), out.c_str());
}

void printSummary(const IndentationRecord& record, const ResponseParameters& r, double failureFraction, const std::string& out) {
  std::printf("settled in %.4g s (%ld steps)%s; loaded block '%s'; stopped: %s\n", record.settleTime, record.settleSteps,
              record.settled ? "" : " (not settled)", record.targetName.c_str(), stopReasonName(record.stopReason));
  std::printf("  peak load          P_max = %.4g N at delta = %.4g mm (within %.3g %% of it from %.4g to %.4g mm)\n", r.peakLoad,
              r.deltaAtPeak * 1e3, 100 * ResponseSettings{}.peakRangeFraction, r.peakRangeFrom * 1e3, r.peakRangeTo * 1e3);
  std::printf("  initial stiffness  K = %.4g N/mm (fit over delta in [%.3g, %.3g] mm)\n", r.stiffness * 1e-3,
              r.fitFrom * 1e3, r.fitTo * 1e3);
  if (r.failureDeflection >= 0)
    std::printf("  failure deflection %.4g mm (load below %.3g x P_max; loaded block moved %.4g mm = %.3g h)\n",
                r.failureDeflection * 1e3, failureFraction,
                r.atFailure.blockDisplacement * 1e3, r.thickness > 0 ? r.atFailure.blockDisplacement / r.thickness : 0.0);
  else
    std::printf("  failure deflection none%s\n", !record.finished()    ? " yet (run incomplete)"
                                               : r.peakLoad > 0 ? " (the load stayed above the failure fraction of P_max)"
                                                                : " (no load: the indenter carried nothing)");
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
  // An unfinished run's "peak" is its last load so far: no verdict on a loading not yet done.
  std::printf("  quasi-static check max KE / W before the peak = %.2e%s\n", r.quasiStaticRatio,
              !record.finished() ? " (run incomplete: no verdict)"
              : r.quasiStatic    ? ""
                                 : " (above the limit: loading too fast, lower indenter.speed)");
  std::printf("  indenter           radius %.4g mm at %.4g mm/s; h = %.4g mm\n", record.indenterRadius * 1e3,
              record.indenterSpeed * 1e3, record.thickness * 1e3);
  if (record.implicit)
    std::printf("  %ld implicit increments (%ld Newton iterations, %ld cut back, %ld dynamic) in %.1f s\n", record.steps,
                record.implicitCounts.iterations, record.implicitCounts.cutbacks, record.implicitCounts.dynamicIncrements,
                record.wallSeconds);
  else
    std::printf("  %ld steps of %.3g s in %.1f s\n", record.steps, record.timeStep, record.wallSeconds);
  std::printf("written to %s (%s)\n", out.c_str(), writtenFiles(out).c_str());
}

// The session of `tessera run`: a new run from the scene, or a resumed one; the arguments checked first.
std::unique_ptr<RunSession> openSession(const RunArguments& a) {
  if (a.resume.empty() == a.scene.empty()) throw InputError("give either a SCENE file (with -o OUTDIR) or --resume OUTDIR");
  if (a.resume.empty() && a.output.empty()) throw InputError("-o OUTDIR is required with a scene");
  if (!a.resume.empty() && !a.output.empty() &&
      !(fs::exists(a.output) && fs::exists(a.resume) && fs::equivalent(a.output, a.resume)))
    throw InputError("-o " + a.output + " with --resume " + a.resume + ": a run resumes in its own folder; leave out -o, or start "
                     "a new run in another folder from the scene with -o");
  if (a.threads < -1 || a.threads > kMaxThreads)
    throw InputError("--threads must be 0 (all cores) or 1 to " + std::to_string(kMaxThreads) + ", got " + std::to_string(a.threads));
  const RunLog log = [](const std::string& line) { std::cerr << "run: " << line << "\n"; };
  std::unique_ptr<RunSession> session;
  if (a.resume.empty()) {
    RunRequest request;
    request.scene = a.scene;
    request.output = a.output;
    request.bundle = a.bundle;
    request.preset = a.preset;
    request.threads = a.threads;
    session = RunSession::start(request, log);
  } else {
    session = RunSession::resume(a.resume, a.bundle, a.preset, a.threads, log);
  }
  return session;
}

// What the run is, before it starts: resumed where, the material and step, each shape's level set.
void printRunHeader(const RunSession& session) {
  const std::string& out = session.output();
  const World& world = session.world();
  const ContactParameters& contact = session.contact();
  if (session.resumed())
    std::fprintf(stderr, "run: resuming %s at t = %.6g s (step %ld)\n", out.c_str(), world.time(), world.stepCount());
  char stiffness[96];
  if (contact.stiffnessRule != StiffnessRule::Span)
    std::snprintf(stiffness, sizeof stiffness, "k_n = E / (w_a + w_b) per pair (%s rule)", stiffnessRuleName(contact.stiffnessRule));
  else
    std::snprintf(stiffness, sizeof stiffness, "k_n = %.4g N/m^3", contact.normalStiffness());
  if (world.settings().method == SolverMethod::Implicit)
    std::fprintf(stderr, "run: %zu bodies, E = %.4g GPa, mu = %.3g, %s, implicit increments of up to %.3g s "
                 "(the explicit step would be %.3g s)\n", session.bundle().bodies.size(), contact.youngsModulus * 1e-9,
                 contact.friction, stiffness, world.timeStep(), world.automaticTimeStep());
  else
    std::fprintf(stderr, "run: %zu bodies, E = %.4g GPa, mu = %.3g, %s, dt = %.3g s (automatic %.3g s)\n",
                 session.bundle().bodies.size(), contact.youngsModulus * 1e-9, contact.friction, stiffness,
                 world.timeStep(), world.automaticTimeStep());
  for (const Shape& shape : session.bundle().shapes)
    std::fprintf(stderr, "run: shape '%s': %s\n", shape.name.c_str(),
                 levelSetPath(shape, session.scene().solver.exactConvexLevelSets, session.scene().solver.exactMeshLevelSets).c_str());
}

// Progress lines and warnings on the terminal, and the stop that Ctrl-C or SIGTERM requests.
RunHooks terminalHooks() {
  RunHooks hooks;
  hooks.progress = [](const Progress& p) {
    if (p.settling) {
      std::fprintf(stderr, "run: settling  KE %.3e J  step %9ld  %6.0f steps/s  ETA %.0f s loading + at most %.0f s settling\n",
                   p.kinetic, p.steps, p.stepsPerSecond, p.etaSeconds, p.settleEtaSeconds);
      return;
    }
    std::fprintf(stderr, "run: delta %7.3f mm  P %9.3f N  KE/W %.2e  contacts %7ld  step %9ld  %6.0f steps/s  ETA %.0f s\n",
                 p.delta * 1e3, p.load, p.externalWork > 0 ? p.kinetic / p.externalWork : 0.0, p.contacts, p.steps,
                 p.stepsPerSecond, p.etaSeconds);
  };
  hooks.interrupted = [] { return stopRequested.load(); };
  hooks.warning = [](const std::string& w) { std::cerr << "run: warning: " << w << "\n"; };
  return hooks;
}

int runTest(const RunArguments& a) {
  const std::unique_ptr<RunSession> session = openSession(a);
  const std::string& out = session->output();
  if (session->finishedAndWritten()) {  // its results are in place: left as they are
    std::fprintf(stderr, "run: %s is complete (stopped: %s at delta = %.4g mm); nothing to resume\n", out.c_str(),
                 stopReasonName(session->record().stopReason), session->record().curve.empty() ? 0.0 : session->record().curve.back().delta * 1e3);
    return 0;
  }
  printRunHeader(*session);
  const RunHooks hooks = terminalHooks();
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  std::string failure;
  try {
    session->run(hooks);
  } catch (const SolverInstability& e) {
    failure = e.what();
  }
  const IndentationRecord& record = session->record();
  if (!record.settled && record.stopReason != StopReason::Interrupted && session->state().phase > 0)
    std::fprintf(stderr,
                 "run: warning: the slab had not settled after %.3g s (kinetic energy above %.3g J) and was loaded as it was; "
                 "damp the settling (damping.local = %.2g here; assets/scenes/default.toml uses 0.3) or give it longer "
                 "(protocol.settle_max_time_ratio)\n",
                 record.settleTime, record.settleKinetic, session->scene().solver.localDamping);
  if (!a.noPlot && !record.curve.empty()) {
    drawPicture("plot_curve.py", out, "curve.png");
    drawPicture("render_snapshots.py", out, "snapshots.png");
  }
  if (session->state().phase == 0) printSettlingSummary(*session, out);
  else printSummary(record, session->response(), session->scene().protocol.failureLoadFraction, out);
  if (!failure.empty()) {
    std::cerr << "tessera: error: the run became unstable and was stopped: " << failure << "\n";
    return 3;
  }
  return record.stopReason == StopReason::Interrupted ? 130 : 0;
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

// The stability map: the measured critical time step of the default slab's indentation against
// Young's modulus and friction, compared with the automatic time step.
//
// For each (E, mu): a reference run at the default time-step factor (0.5), then runs at larger
// factors f (dt = f x 2 / omega_max) up the ladder 1, 1.25, 1.5, 2, 2.5, 3, 4, 6 until one fails,
// and bisection (three halvings) between the last that passed and the first that failed. A run
// fails when the solver stops it (SolverInstability) or when it gives a different answer: the
// load at delta = 0.5 mm or the stiffness K off the reference by more than 2 % (a step beyond the
// limit of a Coulomb-capped spring chatters instead of diverging: the answer goes wrong quietly).
// The critical factor is the smallest failing one; the margin of the automatic step is
// critical / 0.5.
//
// Run: build/bench/stability_map OUT.csv [jobs]   (about 20 min on 2 cores; plot with
// bench/plot_stability_map.py OUT.csv docs/stability_map.png; results: docs/performance.md)
#include "bench/default_slab.h"
#include "run/indentation.h"
#include "run/response.h"
#include "run/run_session.h"
#include "solver/world.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

using namespace tessera;

namespace {

struct Outcome {
  bool stable = false;     // the solver did not stop it
  double load = 0, stiffness = 0;  // N at delta_max, N/m
  double dt = 0;                   // s
  std::string message;
};

// A short indentation (to 0.5 mm at 30 mm/s, local damping 0.3) at time-step factor f.
Outcome indent(const Bundle& slab, double youngsModulus, double friction, double factor) {
  Scene scene;
  scene.contact.youngsModulus = youngsModulus;
  scene.contact.friction = friction;
  scene.contact.spanLength = 0;  // the slab's
  scene.contact.spanInterfaces = 0;
  const ContactParameters contact = resolveSpan(scene.contact, slab, "stability_map");
  scene.solver.threads = 1;
  scene.solver.localDamping = 0.3;
  scene.solver.timeStepFactor = factor;
  scene.solver.allowUnsafeTimeStep = true;
  scene.indenter.speed = 0.03;
  scene.protocol.deltaMax = 0.5e-3;
  scene.protocol.stopOnFailure = false;
  scene.output.checkpointSeconds = 1e9;
  World world(slab.shapes, slab.bodies, contact, scene.solver);
  Outcome o;
  o.dt = world.timeStep();
  IndentationRecord record;
  IndentationState state;
  try {
    runIndentation(world, slab, scene, record, state, RunHooks{});
    o.stable = !record.curve.empty();
    if (o.stable) {
      o.load = record.curve.back().load;
      o.stiffness = analyseResponse(record, ResponseSettings{youngsModulus, contact.spanLength}).stiffness;
    }
  } catch (const SolverInstability& e) {
    o.message = e.what();
  }
  return o;
}

bool agrees(const Outcome& o, const Outcome& reference) {
  return o.stable && std::abs(o.load / reference.load - 1) <= 0.02 &&
         std::abs(o.stiffness / reference.stiffness - 1) <= 0.02;
}

struct Cell {
  double youngsModulus, friction;
  double referenceFactor = 0.5, criticalFactor = 0, lastGoodFactor = 0;
  double automaticDt = 0, criticalDt = 0, referenceLoad = 0, referenceStiffness = 0;
  std::string failure;
};

void measure(const Bundle& slab, Cell& c) {
  const Outcome reference = indent(slab, c.youngsModulus, c.friction, c.referenceFactor);
  c.automaticDt = reference.dt;
  c.referenceLoad = reference.load;
  c.referenceStiffness = reference.stiffness;
  const auto fails = [&](double f, std::string& why) {
    const Outcome o = indent(slab, c.youngsModulus, c.friction, f);
    if (!o.stable) why = "solver stopped";
    else if (!agrees(o, reference))
      why = "answer off (load " + std::to_string(100 * (o.load / reference.load - 1)) + " %, K " +
            std::to_string(100 * (o.stiffness / reference.stiffness - 1)) + " %)";
    return !o.stable || !agrees(o, reference);
  };
  double good = c.referenceFactor, bad = 0;
  std::string why;
  for (double f : {1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 6.0}) {
    if (fails(f, why)) {
      bad = f;
      c.failure = why;
      break;
    }
    good = f;
  }
  if (bad == 0) {
    c.lastGoodFactor = good;
    return;  // stable up to the top of the ladder
  }
  for (int i = 0; i < 3; ++i) {
    const double mid = std::sqrt(good * bad);
    if (fails(mid, why)) {
      bad = mid;
      c.failure = why;
    } else {
      good = mid;
    }
  }
  c.lastGoodFactor = good;
  c.criticalFactor = bad;
  c.criticalDt = bad * c.automaticDt / c.referenceFactor;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: stability_map OUT.csv [jobs]\n");
    return 2;
  }
  const int jobs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 2;
  const Bundle slab = bench::defaultSlab();
  std::vector<Cell> cells;
  for (double e : {3.3e9, 4.2e9, 10e9, 20e9, 40e9, 75e9})
    for (double mu : {0.19, 0.23, 0.5, 1.0, 3.0, 9.0}) {
      Cell c;
      c.youngsModulus = e;
      c.friction = mu;
      cells.push_back(c);
    }
  std::atomic<std::size_t> next{0};
  std::mutex print;
  std::vector<std::thread> workers;
  for (int j = 0; j < jobs; ++j)
    workers.emplace_back([&] {
      for (std::size_t i; (i = next++) < cells.size();) {
        measure(slab, cells[i]);
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "E %5.1f GPa  mu %4.2f  critical factor %s (last good %.3g)  %s\n",
                     cells[i].youngsModulus * 1e-9, cells[i].friction,
                     cells[i].criticalFactor > 0 ? std::to_string(cells[i].criticalFactor).c_str() : "> 6",
                     cells[i].lastGoodFactor, cells[i].failure.c_str());
      }
    });
  for (auto& w : workers) w.join();
  std::ofstream out(argv[1]);
  out << "youngs_modulus_GPa,friction,automatic_dt_s,reference_factor,last_good_factor,critical_factor,critical_dt_s,"
         "margin,reference_load_N,reference_stiffness_N_per_mm,failure\n";
  for (const Cell& c : cells)
    out << c.youngsModulus * 1e-9 << ',' << c.friction << ',' << c.automaticDt << ',' << c.referenceFactor << ','
        << c.lastGoodFactor << ',' << c.criticalFactor << ',' << c.criticalDt << ','
        << (c.criticalFactor > 0 ? c.criticalFactor / c.referenceFactor : 0.0) << ',' << c.referenceLoad << ','
        << c.referenceStiffness * 1e-3 << ",\"" << c.failure << "\"\n";
  return 0;
}

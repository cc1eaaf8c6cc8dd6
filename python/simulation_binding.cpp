// tessera.Simulation: one indentation test (run/run_session.h) driven from Python. Results are
// numpy arrays in SI units; quaternions are (w, x, y, z), body to world.
#include "python/bindings.h"

#include "io/input_error.h"
#include "run/curve_table.h"
#include "run/run_session.h"
#include "run/run_summary.h"

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <iostream>

namespace tessera::python {

namespace py = pybind11;

namespace {

// (n, 3) array of vectors.
py::array_t<double> vectors(const std::vector<Eigen::Vector3d>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) m(i, k) = v[i][k];
  return a;
}

py::array_t<double> quaternions(const std::vector<Eigen::Quaterniond>& q) {
  py::array_t<double> a({static_cast<py::ssize_t>(q.size()), py::ssize_t{4}});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < q.size(); ++i) {
    m(i, 0) = q[i].w();
    m(i, 1) = q[i].x();
    m(i, 2) = q[i].y();
    m(i, 3) = q[i].z();
  }
  return a;
}

template <class T>
py::array_t<T> column(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// The columns of the curve, named as in results.h5 (run/curve_table.h), each a numpy array.
py::dict curveOf(const std::vector<CurveSample>& curve) {
  py::dict d;
  for (const CurveColumn& c : curveColumns()) {
    std::vector<double> v;
    v.reserve(curve.size());
    for (const CurveSample& s : curve) v.push_back(s.*c.field);
    d[c.name] = column(v);
  }
  return d;
}

// Lines of the run's preparation go to stderr, as the command line prints them.
void logLine(const std::string& line) { std::cerr << "tessera: " << line << "\n"; }

// What a sample callback gets as `control`: valid only while the callback runs (the run's own
// control lives on its stack); afterwards every use raises.
struct ControlHandle {
  IndentationControl* control = nullptr;
  IndentationControl& get() const {
    if (!control) throw std::runtime_error("a Control is valid only inside the sample callback it was given to");
    return *control;
  }
};

class Simulation {
public:
  Simulation(const std::string& scene, const std::string& bundle, const std::string& output, const std::string& preset,
             int threads, const std::map<std::string, double>& overrides) {
    RunRequest request;
    request.scene = scene;
    request.bundle = bundle;
    request.output = output;
    request.preset = preset;
    request.threads = threads;
    request.overrides.assign(overrides.begin(), overrides.end());
    session_ = RunSession::start(request, logLine);
  }
  explicit Simulation(std::unique_ptr<RunSession> session) : session_(std::move(session)) {}

  // Runs to the stop. `onSample(sample, control)` after each curve sample; the GIL is released
  // while the World steps. Ctrl-C, or an exception raised by a callback, stops the run as an
  // interrupted one (its record kept, its checkpoint written when it has a folder: it can be
  // resumed), and is raised again here.
  std::string run(const py::object& onSample, const py::object& onProgress) {
    if (running_) throw InputError("this Simulation is running: run() cannot be called again from its own callback");
    running_ = true;
    struct Done {
      bool& flag;
      ~Done() { flag = false; }
    } done{running_};
    RunHooks hooks;
    std::optional<py::error_already_set> raised;
    const auto call = [&](const auto& f) {
      py::gil_scoped_acquire gil;
      if (raised) return;
      try {
        f();
      } catch (py::error_already_set& e) {
        raised.emplace(std::move(e));
      }
    };
    if (!onSample.is_none())
      hooks.sample = [&](const CurveSample& s, IndentationControl& control) {
        call([&] {
          const py::object handle = py::cast(ControlHandle{&control});
          try {
            onSample(s, handle);
          } catch (...) {
            handle.cast<ControlHandle&>().control = nullptr;
            throw;
          }
          handle.cast<ControlHandle&>().control = nullptr;
        });
      };
    if (!onProgress.is_none())
      hooks.progress = [&](const Progress& p) { call([&] { onProgress(p); }); };
    hooks.warning = [this](const std::string& w) {
      py::gil_scoped_acquire gil;
      warnings_.push_back(w);
      logLine("warning: " + w);
    };
    hooks.interrupted = [&] {
      py::gil_scoped_acquire gil;
      return raised.has_value() || PyErr_CheckSignals() != 0;
    };
    {
      py::gil_scoped_release release;
      session_->run(hooks);
    }
    if (raised) throw std::move(*raised);
    if (PyErr_Occurred()) throw py::error_already_set();
    const IndentationRecord& record = session_->record();
    if (!record.settled && record.stopReason != StopReason::Interrupted) {
      char line[200];
      std::snprintf(line, sizeof line, "the slab had not settled after %.3g s (kinetic energy above %.3g J)", record.settleTime,
                    record.settleKinetic);
      warnings_.push_back(line);
      logLine(std::string("warning: ") + line);
    }
    return std::string(stopReasonName(record.stopReason));
  }

  RunSession& session() { return *session_; }
  const RunSession& session() const { return *session_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

private:
  std::unique_ptr<RunSession> session_;
  std::vector<std::string> warnings_;
  bool running_ = false;
};

py::dict contactsOf(const World& world) {
  std::vector<int> a, b, count, sliding;
  std::vector<double> area, elastic;
  std::vector<Eigen::Vector3d> force, normal, point;
  for (int k = 0; k < world.pairCount(); ++k) {
    const PairView p = world.pair(k);
    if (p.nodeContacts == 0) continue;
    a.push_back(p.a);
    b.push_back(p.b);
    count.push_back(p.nodeContacts);
    sliding.push_back(p.slidingNodes);
    area.push_back(p.area);
    elastic.push_back(p.elastic);
    force.push_back(p.force);
    normal.push_back(p.normalForce);
    point.push_back(p.point);
  }
  py::dict d;
  d["a"] = column(a);
  d["b"] = column(b);
  d["force"] = vectors(force);
  d["normal_force"] = vectors(normal);
  d["point"] = vectors(point);
  d["node_contacts"] = column(count);
  d["sliding_nodes"] = column(sliding);
  d["area"] = column(area);
  d["elastic"] = column(elastic);
  return d;
}

// The response parameters as Python sees them (Simulation.response): summary.json's "response"
// (RunSummary, its one definition) by its plain names, in SI units; null (no failure) as None.
py::dict responseOf(const RunSession& session) {
  const RunSummary summary = makeRunSummary(session.scene(), session.bundle(), session.contact(), session.record(),
                                            session.response(), {});
  return py::module_::import("json").attr("loads")(runSummaryJson(summary, false).at("response").dump());
}

// The indenter as Python sees it (Simulation.indenter).
py::dict indenterOf(const Simulation& s) {
  py::dict d;
  const int k = s.session().state().sphere;
  if (k < 0) return d;
  const SphereObstacle& sphere = s.session().world().sphere(k);
  d["centre"] = vectors({sphere.center})[py::int_(0)];
  d["velocity"] = vectors({sphere.velocity})[py::int_(0)];
  d["radius"] = sphere.radius;
  d["reaction"] = vectors({s.session().world().sphereReaction(k)})[py::int_(0)];
  return d;
}

// The energy budget as Python sees it (Simulation.energy): the curve's energy columns, by the
// curve's names.
py::dict energyOf(const Simulation& s) {
  CurveSample now;
  setEnergies(now, s.session().world().energy());
  py::dict d;
  for (const CurveColumn& c : curveColumns())
    if (std::string(c.unit) == "J") d[c.name] = now.*c.field;
  return d;
}

// What a run's callbacks receive: Sample (a curve point), Control (what a sample callback may
// change) and Progress; and the curve's units.
void bindCallbackTypes(py::module_& m) {
  py::dict units;
  for (const CurveColumn& c : curveColumns()) units[c.name] = c.unit;
  m.attr("curve_units") = units;
  // A sample's attributes are the curve's columns, named and in the units of results.h5.
  py::class_<CurveSample> sample(m, "Sample", "One point of the load-deflection record: the columns of sim.curve (SI units).");
  for (const CurveColumn& c : curveColumns())
    sample.def_property_readonly(c.name, [field = c.field](const CurveSample& s) { return s.*field; },
                                 (std::string("unit: ") + c.unit).c_str());

  py::class_<ControlHandle>(m, "Control", "What a sample callback may change, from the next step on (valid only inside it).")
      .def_property(
          "indenter_speed", [](const ControlHandle& h) { return h.get().indenterSpeed; },
          [](const ControlHandle& h, double v) { h.get().indenterSpeed = v; },
          "m/s, downward; negative lifts the indenter, 0 holds it. At most a tenth of the broad-phase margin per step.")
      .def("stop", [](const ControlHandle& h) { h.get().stop = true; },
           "End the run after this sample (stop reason 'requested'; final, not resumable).");

  py::class_<Progress>(m, "Progress")
      .def_readonly("delta", &Progress::delta)
      .def_readonly("load", &Progress::load)
      .def_readonly("steps", &Progress::steps)
      .def_readonly("eta_seconds", &Progress::etaSeconds)
      .def_readonly("settling", &Progress::settling)
      .def_readonly("settle_eta_seconds", &Progress::settleEtaSeconds);
}

}  // namespace

void bindSimulation(py::module_& m) {
  bindCallbackTypes(m);

  py::class_<Simulation>(m, "Simulation",
                         "One indentation test of a slab: a scene, its bundle, the World, the record.")
      .def(py::init<const std::string&, const std::string&, const std::string&, const std::string&, int,
                    const std::map<std::string, double>&>(),
           py::arg("scene"), py::arg("bundle") = "", py::arg("output") = "", py::arg("preset") = "",
           py::arg("threads") = -1, py::arg("overrides") = std::map<std::string, double>{},
           "scene: TOML file (docs/scene.md); bundle: instead of the scene's; output: run folder for the result "
           "files and checkpoints ('' for none); preset: a named preset; threads: -1 the scene's, 0 all cores; "
           "overrides: {'material.friction': 0.5, ...} over the scene's keys (SI).")
      .def_static("resume",
                  [](const std::string& folder, const std::string& bundle, int threads) {
                    return Simulation(RunSession::resume(folder, bundle, "", threads, logLine));
                  },
                  py::arg("folder"), py::arg("bundle") = "", py::arg("threads") = -1,
                  "The stopped run in `folder`, from its checkpoint, exactly as it started.")
      .def("run", &Simulation::run, py::arg("on_sample") = py::none(), py::arg("on_progress") = py::none(),
           "Settle, then load, to the protocol's stop or until on_sample(sample, control) calls control.stop(). "
           "Returns the stop reason.")
      .def("write_outputs",
           [](const Simulation& s) {
             if (s.session().output().empty())
               throw InputError("this Simulation has no run folder; give output=FOLDER when making it");
             s.session().writeOutputs();
           },
           "Write results.h5, curve.csv, summary.json and paraview/ into the run folder (run() does it too).")
      .def_property_readonly("warnings", &Simulation::warnings,
                             "the run's warnings (also printed): loading too fast, bodies sinking while settling, not settled")
      .def_property_readonly("settled", [](const Simulation& s) { return s.session().record().settled; },
                             "whether the slab settled before loading (False: settle_max_time ran out)")
      .def_property_readonly("curve", [](const Simulation& s) { return curveOf(s.session().record().curve); },
                             "dict of numpy arrays, one per column of results.h5's curve (units: tessera.curve_units)")
      .def_property_readonly("response", [](const Simulation& s) { return responseOf(s.session()); },
                             "P_max (N), K (N/m), W (J), failure deflection (m) and mode")
      .def_property_readonly("stop_reason", [](const Simulation& s) { return std::string(stopReasonName(s.session().record().stopReason)); })
      .def_property_readonly("body_names", [](const Simulation& s) { return s.session().world().bodies().name; })
      .def_property_readonly("fixed", [](const Simulation& s) {
        const auto& f = s.session().world().bodies().fixed;
        return column(std::vector<int>(f.begin(), f.end()));
      }, "1 for a support (fixed in the bundle), per body")
      .def_property_readonly("retired", [](const Simulation& s) {
        const auto& r = s.session().world().bodies().retired;
        return column(std::vector<int>(r.begin(), r.end()));
      }, "1 for a body taken out of the computation (fallen clear), per body")
      .def_property_readonly("positions", [](const Simulation& s) { return vectors(s.session().world().bodies().position); },
                             "(n, 3) centroid positions, m")
      .def_property_readonly("orientations",
                             [](const Simulation& s) { return quaternions(s.session().world().bodies().orientation); },
                             "(n, 4) unit quaternions (w, x, y, z), body to world")
      .def_property_readonly("velocities", [](const Simulation& s) { return vectors(s.session().world().bodies().velocity); },
                             "(n, 3) m/s")
      .def_property_readonly("indenter", &indenterOf,
                             "the indenter: centre (m), velocity (m/s), radius (m), reaction of the bodies on it (N)")
      .def("contacts", [](const Simulation& s) { return contactsOf(s.session().world()); },
           "Pairs in contact now: a, b (b < 0: an obstacle, -1 the indenter), force on a (N), its normal_force "
           "part (N; the rest is friction), point (m), node_contacts, sliding_nodes, area (m^2), elastic (J)")
      .def_property_readonly("energy", &energyOf, "the energy budget since the start, J")
      .def_property_readonly("time", [](const Simulation& s) { return s.session().world().time(); }, "s")
      .def_property_readonly("steps", [](const Simulation& s) { return s.session().world().stepCount(); })
      .def_property_readonly("time_step", [](const Simulation& s) { return s.session().world().timeStep(); }, "s")
      .def_property_readonly("output", [](const Simulation& s) { return s.session().output(); });
}

}  // namespace tessera::python

// The `tessera._tessera` extension module; the `tessera` package (python/tessera/) re-exports it.
#include "python/bindings.h"

#include "io/input_error.h"
#include "solver/world.h"

namespace py = pybind11;

PYBIND11_MODULE(_tessera, m) {
  m.doc() = "Tessera: LS-DEM indentation tests of topologically interlocked slabs (C++ core).";
  m.attr("__version__") = TESSERA_VERSION;
  // Bad input (a file, a value) is a ValueError with the command line's one-line message;
  // a write that failed is an OSError; an unstable run a RuntimeError.
  py::register_exception<tessera::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<tessera::WriteError>(m, "WriteError", PyExc_OSError);
  py::register_exception<tessera::SolverInstability>(m, "SolverInstability", PyExc_RuntimeError);
  tessera::python::bindSimulation(m);
  tessera::python::bindSlabs(m);
}

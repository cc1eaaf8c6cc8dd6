#pragma once
#include <pybind11/pybind11.h>

namespace tessera::python {

/// The parts of the `tessera._tessera` extension module, one per concept.
void bindSimulation(pybind11::module_& m);
void bindSlabs(pybind11::module_& m);

}  // namespace tessera::python

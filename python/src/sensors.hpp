// sensors.hpp - the sensors reachable from Python (vkfuse.SimDigit).
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace vkfuse::python {

namespace py = pybind11;

void def_sensors(py::module_& m);

}  // namespace vkfuse::python

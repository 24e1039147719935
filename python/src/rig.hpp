// rig.hpp - recorded datasets and the rig reachable from Python (vkfuse.Dataset, vkfuse.Rig).
#pragma once
#include <pybind11/pybind11.h>

namespace vkfuse::python {

namespace py = pybind11;

void def_rig(py::module_& m);

}  // namespace vkfuse::python

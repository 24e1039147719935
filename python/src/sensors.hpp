// sensors.hpp - the sensors reachable from Python (vkfuse.SimDigit).
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>

#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse::python {

namespace py = pybind11;

void def_sensors(py::module_& m);

// A frame's 8-bit RGB samples as a new (H, W, 3) uint8 array.
py::array_t<std::uint8_t> pixels_of(const Frame& f);

}  // namespace vkfuse::python

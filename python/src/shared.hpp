// shared.hpp - what the Python module's parts share: the process's device,
// fusion specs from keyword arguments, metrics as dicts, the parts' bindings.
#pragma once
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::python {

namespace py = pybind11;

// The context `backend` ("auto", "vulkan", "cpu") asks for, or nullptr for
// the CPU reference path: one Vulkan context per process, opened on first use.
Context* open_backend(const std::string& backend);
// As above, for a choice already parsed (vkfuse.Rig's, from run's options).
Context* open_backend(Backend choice);

FusionSpec spec_of(const std::string& method, const std::string& wavelet, const std::optional<int>& levels,
                   const std::string& mode, const std::string& base_rule, const std::string& detail_rule);

// The metrics `which` names (background_diff where computed).
py::dict to_dict(const Metrics& m, MetricSet which);

// Metric names as a set; throws Error naming "metrics" for an unknown or repeated one.
MetricSet metric_set(const std::vector<std::string>& names);

// The module's parts: fuse, metrics, max_levels (fusion.cpp); Plan (plan.cpp).
void def_fusion(py::module_& m);
void def_plan(py::module_& m);

}  // namespace vkfuse::python

// The Python module's compiled part, vkfuse._vkfuse: its bindings and the
// translation of the library's errors. python/vkfuse (pure Python) is what
// users import; it takes arrays as numpy, PyTorch and digit-interface users
// hold them and hands this module C-ordered landscape RGB frames:
//
//   fused = _vkfuse.fuse(frames, sensors=S, ...)       S x K frames -> float32 (S, H, W[, C])
//   _vkfuse.metrics(image, background=None)            fusion.cpp
//   _vkfuse.Plan(...).run(frames, out=None)             plan.cpp
//   _vkfuse.SimDigit, Dataset, Rig                      sensors.cpp, rig.cpp
//
// Bad arguments and shapes raise ValueError, everything else vkfuse.Error,
// with the library's one-line messages, option names as Python spells them.
#include <pybind11/pybind11.h>

#include <algorithm>
#include <string>
#include <vector>

#include "commands.hpp"
#include "device_tensor.hpp"
#include "rig.hpp"
#include "sensors.hpp"
#include "shared.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/version.hpp"

namespace vkfuse::python {
namespace {

// The library names what it refuses as the command line spells it (--levels,
// --base-rule/--detail-rule); in Python those are keyword arguments (levels,
// base_rule). Only the options of the commands Python reaches (fuse, run:
// vkfuse.fuse, Plan, Rig) are rewritten, and only as whole words, so a path
// or a value that contains "--" reads as given.
std::string python_words(std::string message) {
    // Letters, '-', '_' extend a word; a '"' opens or closes a value the user gave.
    const auto word_char = [](char c) { return (c >= 'a' && c <= 'z') || c == '-' || c == '_' || c == '"'; };
    std::vector<std::string> options;
    for (const cli::Command* command : {&cli::fuse_command, &cli::run_command})
        for (const cli::OptionSpec& o : command->spec.options)
            if (o.name.starts_with("--")) options.emplace_back(o.name);
    // Longest first: --skip-threshold is not read as --skip.
    std::sort(options.begin(), options.end(), [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
    for (const std::string& name : options) {
        for (std::size_t at = message.find(name); at != std::string::npos; at = message.find(name, at + 1)) {
            const std::size_t end = at + name.size();
            if ((at > 0 && word_char(message[at - 1])) || (end < message.size() && word_char(message[end]))) continue;
            std::string keyword = name.substr(2);
            for (char& c : keyword) c = c == '-' ? '_' : c;
            message.replace(at, name.size(), keyword);
        }
    }
    return message;
}

}  // namespace
}  // namespace vkfuse::python

PYBIND11_MODULE(_vkfuse, m) {
    using namespace vkfuse;
    using namespace vkfuse::python;
    m.doc() = "vkfuse: fusion of tactile frames lit differently (Vulkan compute, CPU reference)";
    m.attr("__version__") = std::string(kVersion);
    static py::exception<Error> error(m, "Error");
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const OutOfMemory& e) {
            PyErr_SetString(PyExc_MemoryError, python_words(e.what()).c_str());
        } catch (const Error& e) {
            const std::string message = python_words(e.what());
            if (e.kind() == ErrorKind::InvalidArgument || e.kind() == ErrorKind::Shape)
                PyErr_SetString(PyExc_ValueError, message.c_str());
            else
                error(message.c_str());
        }
    });

    def_fusion(m);
    def_plan(m);
    def_device_tensor(m);
    def_sensors(m);
    def_rig(m);
}

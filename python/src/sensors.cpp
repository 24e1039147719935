// vkfuse.SimDigit: the simulated DIGIT from Python, on a virtual clock of its
// own (as fast as the host renders, deterministic for a seed):
//
//   sim = vkfuse.SimDigit(object="coin")
//   white, green = sim.capture([(15, 15, 15), (0, 15, 0)])   # uint8 (240, 320, 3), each lit by one setting
//   frame = sim.grab()                                       # {"pixels", "timestamp", "index"}
#include "sensors.hpp"

#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/sim_digit.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse::python {
namespace {

Illumination setting_of(const std::vector<int>& levels) {
    if (levels.size() != 3)
        throw Error(ErrorKind::InvalidArgument,
                    "illumination: " + std::to_string(levels.size()) + " levels given; a DIGIT has 3 (r, g, b)");
    return Illumination(levels);
}

class PySimDigit {
public:
    PySimDigit(const std::string& object, bool vga, std::uint64_t seed, double press_depth_mm, double x, double y,
               bool camera_auto, const std::string& serial) {
        SimDigitOptions o;
        o.object = object, o.vga = vga, o.seed = seed, o.press_depth_mm = press_depth_mm, o.x = x, o.y = y;
        o.camera_auto = camera_auto, o.serial = serial;
        o.clock = clock_ = make_virtual_clock();
        sim_ = std::make_unique<SimDigit>(o);
    }

    void set_illumination(const std::vector<int>& levels) { sim_->set_illumination(setting_of(levels)); }
    void set_object(const std::string& object, double press_depth_mm) { sim_->set_object(object, press_depth_mm); }

    py::dict grab() {
        Frame f;
        {
            py::gil_scoped_release unlocked;
            f = sim_->grab();
        }
        py::dict d;
        d["pixels"] = pixels_of(f);
        d["timestamp"] = f.timestamp;
        d["index"] = f.index;
        return d;
    }

    // One frame lit entirely by each setting, in order. The switch timing is
    // measured on first use, as the rig does for a sensor.
    py::list capture(const std::vector<std::vector<int>>& settings) {
        IlluminationSequence sequence;
        for (const auto& s : settings) sequence.push_back(setting_of(s));
        if (sequence.empty()) throw Error(ErrorKind::InvalidArgument, "settings: none given");
        if (!switcher_ || sequence != last_sequence_) {
            py::gil_scoped_release unlocked;
            if (!timing_) timing_ = measure_switch_timing(*sim_, *clock_);
            switcher_.emplace(*sim_, clock_, *timing_);
            last_sequence_ = sequence;
        }
        std::vector<Frame> frames;
        {
            py::gil_scoped_release unlocked;
            frames = switcher_->next_cycle(sequence);
        }
        py::list out;
        for (const Frame& f : frames) out.append(pixels_of(f));
        return out;
    }

private:
    std::shared_ptr<Clock> clock_;
    std::unique_ptr<SimDigit> sim_;
    std::optional<SwitchTiming> timing_;
    std::optional<Switcher> switcher_;
    IlluminationSequence last_sequence_;
};

}  // namespace

py::array_t<std::uint8_t> pixels_of(const Frame& f) {
    py::array_t<std::uint8_t> out({py::ssize_t(f.height), py::ssize_t(f.width), py::ssize_t(3)});
    std::copy(f.pixels.begin(), f.pixels.end(), out.mutable_data());
    return out;
}

void def_sensors(py::module_& m) {
    py::class_<PySimDigit>(m, "SimDigit", "The simulated DIGIT (gel, three LEDs, an object pressed in), on a virtual clock.")
        .def(py::init<const std::string&, bool, std::uint64_t, double, double, double, bool, const std::string&>(),
             py::arg("object") = "coin", py::arg("vga") = false, py::arg("seed") = 1, py::arg("press_depth_mm") = 1.0,
             py::arg("x") = 0.5, py::arg("y") = 0.5, py::arg("camera_auto") = false, py::arg("serial") = "SIM-0001")
        .def("set_illumination", &PySimDigit::set_illumination, py::arg("levels"),
             "Requests (r, g, b), each 0..15; it lights the gel after the LED latency.")
        .def("set_object", &PySimDigit::set_object, py::arg("object"), py::arg("press_depth_mm") = 1.0)
        .def("grab", &PySimDigit::grab, "The next frame: {pixels (H, W, 3) uint8, timestamp, index}.")
        .def("capture", &PySimDigit::capture, py::arg("settings"),
             "One uint8 frame lit entirely by each (r, g, b) setting, in order.");
}

}  // namespace vkfuse::python

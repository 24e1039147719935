// vkfuse._vkfuse.Plan: a plan for one shape, K, S and method, on the device
// when there is one, else the CPU reference path with the same interface.
// python/vkfuse/_plan.py wraps it with the caller's dtypes and layouts.
//
// A Plan is one thread's at a time: calls from several threads are
// serialised, each waiting its turn with the GIL released (so the thread
// holding the plan can finish); different plans run in parallel.
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>

#include "arrays.hpp"
#include "device_tensor.hpp"
#include "shared.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/rig/rig.hpp"
#include "vkfuse/vk/interop.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::python {
namespace {

std::string shape_text(int h, int w, int c) {
    return std::to_string(h) + "x" + std::to_string(w) + "x" + std::to_string(c);
}

class PyPlan {
public:
    PyPlan(int height, int width, int channels, int frames, int sensors, const std::string& dtype,
           const std::string& method, const std::string& wavelet, const std::optional<int>& levels,
           const std::string& mode, const std::string& base_rule, const std::string& detail_rule,
           const std::vector<std::string>& metrics, const std::string& backend, bool on_device) {
        config_.fusion = spec_of(method, wavelet, levels, mode, base_rule, detail_rule);
        config_.height = height, config_.width = width, config_.channels = channels, config_.frames = frames;
        if (sensors < 1 || std::size_t(sensors) > kMaxRigSensors)
            throw Error(ErrorKind::InvalidArgument, "sensors " + std::to_string(sensors) + ": must be from 1 to " +
                                                        std::to_string(kMaxRigSensors));
        config_.sensors = sensors;
        if (dtype != "uint8" && dtype != "float32")
            throw Error(ErrorKind::InvalidArgument, "dtype " + dtype + ": expected uint8 or float32");
        config_.input = dtype == "uint8" ? PixelType::U8 : PixelType::F32;
        config_.metrics = metric_set(metrics);
        validate(config_.fusion, height, width, channels, frames);
        context_ = open_backend(backend);
        if (on_device) {
            if (!context_) throw Error(ErrorKind::InvalidArgument, "on_device: needs the Vulkan backend; this plan is cpu");
            std::vector<std::int64_t> shape = {sensors, height, width};
            if (channels != 1) shape.push_back(channels);
            on_device_.emplace(DeviceTensor::exportable(*context_, std::move(shape)));
            plan_.emplace(make_plan(*context_, config_, {{}, on_device_->range()}));
        } else if (context_) {
            plan_.emplace(*context_, config_);
        }
        backgrounds_.resize(std::size_t(sensors));
    }

    void set_background(const py::handle& background_in, int sensor) {
        if (sensor < 0 || sensor >= config_.sensors)
            throw Error(ErrorKind::InvalidArgument, "sensor " + std::to_string(sensor) + ": the plan has sensors 0 to " +
                                                        std::to_string(config_.sensors - 1));
        Frames bg = to_frame(background_in, "background");
        check(bg, "background");
        const std::unique_lock turn = take_turn();
        if (plan_) {
            plan_->set_background(sensor, bg.views().front());
        } else {
            backgrounds_[std::size_t(sensor)] = bg.images().front();
        }
    }

    // frames: S x K arrays, sensor-major. (float32 (S, H, W[, C]), [metrics dict per sensor]).
    py::tuple run(const py::sequence& frames_in, const py::object& out) {
        Frames frames = to_frames(frames_in, "frames");
        const std::size_t want = std::size_t(config_.frames) * std::size_t(config_.sensors);
        if (frames.arrays.size() != want)
            throw Error(ErrorKind::InvalidArgument, "frames: " + std::to_string(frames.arrays.size()) +
                                                        " given; the plan fuses " + std::to_string(config_.frames) +
                                                        " for each of " + std::to_string(config_.sensors) + " sensor(s)");
        check(frames, "frames[0]");
        const int S = config_.sensors;
        std::vector<Metrics> m(static_cast<std::size_t>(S));
        if (on_device_) {
            if (!out.is_none()) throw Error(ErrorKind::InvalidArgument, "out: the plan keeps its images on the device");
            const std::unique_lock turn = take_turn();
            const std::vector<FrameView> views = frames.views();
            {
                py::gil_scoped_release unlocked;
                plan_->run(views);
                for (int s = 0; s < S && !config_.metrics.empty(); ++s) m[std::size_t(s)] = plan_->metrics(s);
            }
            return py::make_tuple(*on_device_, scores_of(m));
        }
        py::array_t<float> fused = fused_array(out, config_.sensors, config_.height, config_.width,
                                               config_.channels, frames.gray);
        float* const into = fused.mutable_data();
        const std::unique_lock turn = take_turn();
        if (plan_) {
            const std::vector<FrameView> views = frames.views();
            py::gil_scoped_release unlocked;
            plan_->run(views);
            for (int s = 0; s < S; ++s) {
                put(into, s, plan_->fused(s));
                if (!config_.metrics.empty()) m[std::size_t(s)] = plan_->metrics(s);
            }
        } else {
            if (config_.metrics.has(Metric::BackgroundDiff))
                for (int s = 0; s < S; ++s)
                    if (!backgrounds_[std::size_t(s)])
                        throw Error(ErrorKind::InvalidArgument,
                                    "background_diff: set_background() first (sensor " + std::to_string(s) + ")");
            const std::vector<ImageD> images = frames.images();
            py::gil_scoped_release unlocked;
            for (int s = 0; s < S; ++s) {
                const auto mine = std::span(images).subspan(std::size_t(s * config_.frames), std::size_t(config_.frames));
                const ImageD f = fuse_reference(mine, config_.fusion);
                const std::optional<ImageD>& bg = backgrounds_[std::size_t(s)];
                if (!config_.metrics.empty()) m[std::size_t(s)] = metrics_reference(f, bg ? &*bg : nullptr, config_.metrics);
                put(into, s, f);
            }
        }
        return py::make_tuple(fused, scores_of(m));
    }

    std::string backend() const { return plan_ ? "vulkan" : "cpu"; }
    int sensors() const { return config_.sensors; }

    // The median of `runs` cycles of Plan::run timed in C++ alone (results
    // read in place, nothing converted): what plan.run's Python path is
    // compared with (bench/python_overhead.py).
    double cpp_cycle_ms(const py::sequence& frames_in, int runs) {
        if (!plan_) throw Error(ErrorKind::InvalidArgument, "cpp_cycle_ms: times the Vulkan plan; this one is cpu");
        if (runs < 1) throw Error(ErrorKind::InvalidArgument, "runs " + std::to_string(runs) + ": must be >= 1");
        Frames frames = to_frames(frames_in, "frames");
        check(frames, "frames[0]");
        const std::vector<FrameView> views = frames.views();
        std::vector<double> ms;
        const std::unique_lock turn = take_turn();
        py::gil_scoped_release unlocked;
        for (int i = 0; i < runs; ++i) {
            const auto start = std::chrono::steady_clock::now();
            plan_->run(views);
            for (int s = 0; s < config_.sensors; ++s) {
                if (config_.want_fused) (void)plan_->fused(s).data.front();
                if (!config_.metrics.empty()) (void)plan_->metrics(s);
            }
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        std::nth_element(ms.begin(), ms.begin() + std::ptrdiff_t(ms.size() / 2), ms.end());
        return ms[ms.size() / 2];
    }

private:
    py::list scores_of(const std::vector<Metrics>& m) const {
        py::list scores;
        for (const Metrics& one : m) scores.append(to_dict(one, config_.metrics));
        return scores;
    }

    // This thread's turn with the plan, waited for without the GIL.
    std::unique_lock<std::mutex> take_turn() {
        std::unique_lock lock(mutex_, std::try_to_lock);
        if (!lock.owns_lock()) {
            py::gil_scoped_release unlocked;
            lock.lock();
        }
        return lock;
    }

    void check(const Frames& f, const std::string& what) const {
        if (f.height != config_.height || f.width != config_.width || f.channels != config_.channels)
            throw Error(ErrorKind::Shape, what + ": " + shape_text(f.height, f.width, f.channels) + "; the plan takes " +
                                              shape_text(config_.height, config_.width, config_.channels));
        if (f.type != config_.input)
            throw Error(ErrorKind::InvalidArgument, what + ": dtype " + f.arrays[0].dtype().attr("name").cast<std::string>() +
                                                       "; the plan takes " +
                                                       (config_.input == PixelType::U8 ? "uint8" : "float32 or float64"));
    }

    PlanConfig config_;
    Context* context_ = nullptr;
    // on_device: where the fused images stay (each run() returns it, sharing
    // the memory). Declared before plan_: the plan's buffers outlive the plan.
    std::optional<DeviceTensor> on_device_;
    std::optional<Plan> plan_;
    std::vector<std::optional<ImageD>> backgrounds_;  // the CPU path's, per sensor
    std::mutex mutex_;                                // whose turn it is
};

}  // namespace

void def_plan(py::module_& m) {
    py::class_<PyPlan>(m, "Plan", "Built once for a shape, K, S and method; run() every cycle.")
        .def(py::init<int, int, int, int, int, const std::string&, const std::string&, const std::string&,
                      const std::optional<int>&, const std::string&, const std::string&, const std::string&,
                      const std::vector<std::string>&, const std::string&, bool>(),
             py::arg("height"), py::arg("width"), py::arg("channels") = 3, py::arg("frames") = 2,
             py::arg("sensors") = 1, py::arg("dtype") = "uint8", py::arg("method") = "wavelet",
             py::arg("wavelet") = "bior4.4", py::arg("levels") = py::none(), py::arg("mode") = "periodization",
             py::arg("base_rule") = "mean", py::arg("detail_rule") = "max-abs",
             py::arg("metrics") = std::vector<std::string>{"sharpness", "contrast"}, py::arg("backend") = "auto",
             py::arg("on_device") = false)
        .def("set_background", &PyPlan::set_background, py::arg("background"), py::arg("sensor") = 0)
        .def("run", &PyPlan::run, py::arg("frames"), py::arg("out") = py::none(),
             "Fuses one cycle's S x K frames (sensor-major): (float32 (S, H, W[, C]), [metrics per sensor]).")
        .def_property_readonly("backend", &PyPlan::backend)
        .def_property_readonly("sensors", &PyPlan::sensors)
        .def("cpp_cycle_ms", &PyPlan::cpp_cycle_ms, py::arg("frames"), py::arg("runs") = 20,
             "Median ms of Plan::run timed in C++ (the baseline plan.run's overhead is measured against).");
}

}  // namespace vkfuse::python

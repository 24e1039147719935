// The Python module `vkfuse` (its compiled part, vkfuse._vkfuse):
//
//   fused = vkfuse.fuse(frames, method="wavelet", ...)      one call, any backend
//   m = vkfuse.metrics(image, background=None)              {"sharpness", "contrast"[, "background_diff"]}
//   plan = vkfuse.Plan(240, 320, channels=3, frames=2, ...)  built once: pipelines, buffers
//   fused, m = plan.run(frames)                              per cycle, the GIL released while it runs
//   frames = vkfuse.SimDigit().capture([(15,15,15), (0,15,0)])  the simulated DIGIT (sensors.cpp)
//
// Bad arguments and shapes raise ValueError, everything else vkfuse.Error,
// with the library's one-line messages. The Vulkan context is opened once per
// process, on first use, and shared by every call and plan.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <list>
#include <memory>
#include <mutex>
#include <optional>

#include "arrays.hpp"
#include "shared.hpp"
#include "rig.hpp"
#include "sensors.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/version.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::python {
namespace {

// vkfuse.fuse() and vkfuse.metrics() plans, kept per configuration, so that
// calling them in a loop costs a run, not a plan (buffers, descriptor sets,
// the recorded commands). A plan is lent to one caller at a time: two threads
// fusing the same shape get two plans.
class PlanCache {
public:
    std::unique_ptr<Plan> take(Context& context, const PlanConfig& c) {
        {
            std::lock_guard lock(mutex_);
            for (auto it = plans_.begin(); it != plans_.end(); ++it)
                if (same(it->get()->config(), c)) {
                    std::unique_ptr<Plan> plan = std::move(*it);
                    plans_.erase(it);
                    return plan;
                }
        }
        return std::make_unique<Plan>(context, c);
    }
    void give_back(std::unique_ptr<Plan> plan) {
        std::lock_guard lock(mutex_);
        plans_.push_front(std::move(plan));
        if (plans_.size() > kKept) plans_.pop_back();
    }

private:
    static constexpr std::size_t kKept = 8;  // the most recently used configurations
    std::mutex mutex_;
    std::list<std::unique_ptr<Plan>> plans_;

    static bool same(const PlanConfig& a, const PlanConfig& b) {
        const FusionSpec &f = a.fusion, &g = b.fusion;
        return a.fuse == b.fuse && f.method == g.method && f.levels == g.levels && f.wavelet == g.wavelet &&
               f.mode == g.mode && f.base_rule == g.base_rule && f.detail_rule == g.detail_rule &&
               a.height == b.height && a.width == b.width && a.channels == b.channels && a.frames == b.frames &&
               a.sensors == b.sensors && a.input == b.input && a.want_fused == b.want_fused && a.metrics == b.metrics;
    }
};

// The process's Vulkan context, opened on first use (the one device a Python
// process shares, like a default CUDA device; empty when there is no usable
// device), and the plans made on it, released before it.
struct ProcessDevice {
    std::optional<Context> context;
    PlanCache plans;
};

ProcessDevice& process_device() {
    static std::once_flag once;
    static ProcessDevice device;
    std::call_once(once, [] { device.context = vkfuse::open_backend(Backend::Auto, "backend"); });
    return device;
}

// Runs `use` on a cached plan of c (the GIL released by the caller).
template <class Use>
void with_plan(const PlanConfig& c, Use&& use) {
    ProcessDevice& device = process_device();
    std::unique_ptr<Plan> plan = device.plans.take(*device.context, c);
    use(*plan);  // a plan that threw (bad input) is dropped, not kept
    device.plans.give_back(std::move(plan));
}

}  // namespace

// The context `backend` asks for, or nullptr for the CPU reference path.
Context* open_backend(const std::string& backend) {
    const std::optional<Backend> choice = parse_backend(backend);
    if (!choice) throw Error(ErrorKind::InvalidArgument, "backend " + backend + ": expected cpu, vulkan or auto");
    if (*choice == Backend::Cpu) return nullptr;
    std::optional<Context>& context = process_device().context;
    // No device: asked again, so `vulkan` raises the library's own message.
    if (!context && *choice == Backend::Vulkan) vkfuse::open_backend(Backend::Vulkan, "backend");
    return context ? &*context : nullptr;
}

FusionSpec spec_of(const std::string& method, const std::string& wavelet, const std::optional<int>& levels,
                   const std::string& mode, const std::string& base_rule, const std::string& detail_rule) {
    FusionSpec s;
    s.method = parse_method(method);
    s.wavelet = parse_wavelet(wavelet);
    s.levels = levels.value_or(0);
    if (levels && *levels < 1) throw Error(ErrorKind::InvalidArgument, "levels " + std::to_string(*levels) + ": must be >= 1");
    s.mode = parse_wavelet_mode(mode);
    s.base_rule = parse_rule(base_rule, "base_rule");
    s.detail_rule = parse_rule(detail_rule, "detail_rule");
    return s;
}

py::dict to_dict(const Metrics& m, MetricSet which) {
    py::dict d;
    if (which.has(Metric::Sharpness)) d["sharpness"] = m.sharpness;
    if (which.has(Metric::Contrast)) d["contrast"] = m.contrast;
    if (m.background_diff) d["background_diff"] = *m.background_diff;
    return d;
}

namespace {

MetricSet metric_set(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ",") + n;
    if (names.empty()) return {};
    const std::optional<MetricSet> s = MetricSet::parse(list);
    if (!s)
        throw Error(ErrorKind::InvalidArgument,
                    "metrics " + list + ": expected names among sharpness, contrast, background_diff, each once");
    return *s;
}

py::array_t<float> fuse(const py::sequence& frames_in, const std::string& method, const std::string& wavelet,
                        const std::optional<int>& levels, const std::string& mode, const std::string& base_rule,
                        const std::string& detail_rule, const std::string& backend) {
    const FusionSpec spec = spec_of(method, wavelet, levels, mode, base_rule, detail_rule);
    Frames frames = to_frames(frames_in, "frames");
    validate(spec, frames.height, frames.width, frames.channels, int(frames.arrays.size()));
    Context* context = open_backend(backend);
    if (!context) {
        const std::vector<ImageD> images = frames.images();
        ImageD fused;
        {
            py::gil_scoped_release unlocked;
            fused = fuse_reference(images, spec);
        }
        return to_array(fused, frames.gray);
    }
    PlanConfig c;
    c.fusion = spec;
    c.height = frames.height, c.width = frames.width, c.channels = frames.channels;
    c.frames = int(frames.arrays.size());
    c.input = frames.type;
    c.metrics = {};
    const std::vector<FrameView> views = frames.views();
    Image fused;
    {
        py::gil_scoped_release unlocked;
        with_plan(c, [&](Plan& plan) {
            plan.run(views);
            fused = plan.fused(0);
        });
    }
    return to_array(fused, frames.gray);
}

py::dict metrics(const py::handle& image_in, const py::object& background_in, const std::string& backend) {
    Frames image = to_frame(image_in, "image");
    std::optional<Frames> background;
    if (!background_in.is_none()) {
        background = to_frame(background_in, "background");
        if (background->height != image.height || background->width != image.width ||
            background->channels != image.channels)
            throw Error(ErrorKind::Shape, "background: shape differs from the image's");
    }
    const MetricSet which = background ? MetricSet::all() : MetricSet{Metric::Sharpness, Metric::Contrast};
    Context* context = open_backend(backend);
    Metrics m;
    if (!context) {
        const ImageD img = image.images().front();
        const std::optional<ImageD> bg = background ? std::optional(background->images().front()) : std::nullopt;
        py::gil_scoped_release unlocked;
        m = metrics_reference(img, bg ? &*bg : nullptr, which);
    } else {
        PlanConfig c;
        c.fuse = false;
        c.height = image.height, c.width = image.width, c.channels = image.channels;
        c.frames = 1;
        c.input = image.type;
        c.want_fused = false;
        c.metrics = which;
        // A plan reads its background as it reads frames: same element type.
        if (background && background->type != image.type)
            throw Error(ErrorKind::InvalidArgument, "background: dtype differs from the image's");
        const std::vector<FrameView> views = image.views();
        const std::optional<FrameView> bg = background ? std::optional(background->views().front()) : std::nullopt;
        py::gil_scoped_release unlocked;
        with_plan(c, [&](Plan& plan) {
            if (bg) plan.set_background(0, *bg);
            plan.run(views);
            m = plan.metrics(0);
        });
    }
    return to_dict(m, which);
}

// A plan for one shape, K and method: on the device when there is one, else
// the CPU reference path with the same interface. A Plan is one thread's at a
// time: calls from several threads are serialised, each waiting its turn with
// the GIL released (so the thread holding the plan can finish).
class PyPlan {
public:
    PyPlan(int height, int width, int channels, int frames, const std::string& dtype, const std::string& method,
           const std::string& wavelet, const std::optional<int>& levels, const std::string& mode,
           const std::string& base_rule, const std::string& detail_rule, const std::vector<std::string>& metrics,
           const std::string& backend) {
        config_.fusion = spec_of(method, wavelet, levels, mode, base_rule, detail_rule);
        config_.height = height, config_.width = width, config_.channels = channels, config_.frames = frames;
        if (dtype != "uint8" && dtype != "float32")
            throw Error(ErrorKind::InvalidArgument, "dtype " + dtype + ": expected uint8 or float32");
        config_.input = dtype == "uint8" ? PixelType::U8 : PixelType::F32;
        config_.metrics = metric_set(metrics);
        validate(config_.fusion, height, width, channels, frames);
        context_ = open_backend(backend);
        if (context_) plan_.emplace(*context_, config_);
    }

    void set_background(const py::handle& background_in) {
        Frames bg = to_frame(background_in, "background");
        check(bg, "background");
        const std::unique_lock turn = take_turn();
        if (plan_) {
            plan_->set_background(0, bg.views().front());
        } else {
            background_ = bg.images().front();
        }
    }

    py::tuple run(const py::sequence& frames_in) {
        Frames frames = to_frames(frames_in, "frames");
        if (int(frames.arrays.size()) != config_.frames)
            throw Error(ErrorKind::InvalidArgument, "frames: " + std::to_string(frames.arrays.size()) +
                                                        " given; the plan fuses " + std::to_string(config_.frames));
        check(frames, "frames[0]");
        const std::unique_lock turn = take_turn();
        if (config_.metrics.has(Metric::BackgroundDiff) && !plan_ && !background_)
            throw Error(ErrorKind::InvalidArgument, "background_diff: set_background() first");
        Metrics m;
        py::array_t<float> fused;
        if (plan_) {
            const std::vector<FrameView> views = frames.views();
            {
                py::gil_scoped_release unlocked;
                plan_->run(views);
            }
            fused = to_array(plan_->fused(0), frames.gray);
            if (!config_.metrics.empty()) m = plan_->metrics(0);
        } else {
            const std::vector<ImageD> images = frames.images();
            ImageD out;
            {
                py::gil_scoped_release unlocked;
                out = fuse_reference(images, config_.fusion);
                if (!config_.metrics.empty())
                    m = metrics_reference(out, background_ ? &*background_ : nullptr, config_.metrics);
            }
            fused = to_array(out, frames.gray);
        }
        return py::make_tuple(fused, to_dict(m, config_.metrics));
    }

    std::string backend() const { return plan_ ? "vulkan" : "cpu"; }

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
            if (config_.want_fused) (void)plan_->fused(0).data.front();
            if (!config_.metrics.empty()) (void)plan_->metrics(0);
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        std::nth_element(ms.begin(), ms.begin() + std::ptrdiff_t(ms.size() / 2), ms.end());
        return ms[ms.size() / 2];
    }

private:
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
            throw Error(ErrorKind::Shape, what + ": " + std::to_string(f.height) + "x" + std::to_string(f.width) + "x" +
                                              std::to_string(f.channels) + "; the plan takes " +
                                              std::to_string(config_.height) + "x" + std::to_string(config_.width) +
                                              "x" + std::to_string(config_.channels));
        if (f.type != config_.input)
            throw Error(ErrorKind::InvalidArgument, what + ": dtype " + f.arrays[0].dtype().attr("name").cast<std::string>() +
                                                       "; the plan takes " +
                                                       (config_.input == PixelType::U8 ? "uint8" : "float32 or float64"));
    }

    PlanConfig config_;
    Context* context_ = nullptr;
    std::optional<Plan> plan_;
    std::optional<ImageD> background_;  // the CPU path's
    std::mutex mutex_;                  // whose turn it is
};

// The library names what it refuses as the command line spells it (--levels,
// --base-rule/--detail-rule); in Python those are keyword arguments (levels,
// base_rule). Only these option names are rewritten, and only as whole words,
// so a path or a value that contains "--" reads as given.
std::string python_words(std::string message) {
    static constexpr const char* kOptions[] = {"--levels", "--wavelet", "--mode",    "--method",
                                               "--base-rule", "--detail-rule", "--metrics", "--backend"};
    // Letters, '-', '_' extend a word; a '"' opens or closes a value the user gave.
    const auto word_char = [](char c) { return (c >= 'a' && c <= 'z') || c == '-' || c == '_' || c == '"'; };
    for (const char* option : kOptions) {
        const std::string name(option);
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

    m.def("fuse", &fuse, py::arg("frames"), py::arg("method") = "wavelet", py::arg("wavelet") = "bior4.4",
          py::arg("levels") = py::none(), py::arg("mode") = "periodization", py::arg("base_rule") = "mean",
          py::arg("detail_rule") = "max-abs", py::arg("backend") = "auto",
          "Fuses K frames of one shape (uint8 scaled by 1/255, float32 or float64; (H, W) or (H, W, C)) into a "
          "float32 array of their shape. levels: None for the method's default (laplacian 4, wavelet 3).");
    m.def("metrics", &metrics, py::arg("image"), py::arg("background") = py::none(), py::arg("backend") = "auto",
          "Sharpness, RMS contrast and, with a background, the mean absolute difference from it.");
    py::class_<PyPlan>(m, "Plan", "Built once for a shape, K and method; run() every cycle.")
        .def(py::init<int, int, int, int, const std::string&, const std::string&, const std::string&,
                      const std::optional<int>&, const std::string&, const std::string&, const std::string&,
                      const std::vector<std::string>&, const std::string&>(),
             py::arg("height"), py::arg("width"), py::arg("channels") = 3, py::arg("frames") = 2,
             py::arg("dtype") = "uint8", py::arg("method") = "wavelet", py::arg("wavelet") = "bior4.4",
             py::arg("levels") = py::none(), py::arg("mode") = "periodization", py::arg("base_rule") = "mean",
             py::arg("detail_rule") = "max-abs",
             py::arg("metrics") = std::vector<std::string>{"sharpness", "contrast"}, py::arg("backend") = "auto")
        .def("set_background", &PyPlan::set_background, py::arg("background"))
        .def("run", &PyPlan::run, py::arg("frames"), "Fuses one cycle's frames: (fused, metrics dict).")
        .def_property_readonly("backend", &PyPlan::backend)
        .def("cpp_cycle_ms", &PyPlan::cpp_cycle_ms, py::arg("frames"), py::arg("runs") = 20,
             "Median ms of Plan::run timed in C++ (the baseline plan.run's overhead is measured against).");
    def_sensors(m);
    def_rig(m);
}

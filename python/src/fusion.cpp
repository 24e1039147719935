// vkfuse.fuse() and vkfuse.metrics() (the compiled part; python/vkfuse
// wraps them with numpy, PyTorch and digit-interface conventions), and what
// every part of the module shares (shared.hpp).
#include <pybind11/stl.h>

#include <list>
#include <memory>
#include <mutex>
#include <optional>

#include "arrays.hpp"
#include "shared.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
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
    return open_backend(*choice);
}

Context* open_backend(Backend choice) {
    if (choice == Backend::Cpu) return nullptr;
    std::optional<Context>& context = process_device().context;
    // No device: asked again, so `vulkan` raises the library's own message.
    if (!context && choice == Backend::Vulkan) vkfuse::open_backend(Backend::Vulkan, "backend");
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

namespace {

// frames: S x K arrays, sensor-major. The result: float32 (S, H, W[, C]).
py::array_t<float> fuse(const py::sequence& frames_in, int sensors, const std::string& method,
                        const std::string& wavelet, const std::optional<int>& levels, const std::string& mode,
                        const std::string& base_rule, const std::string& detail_rule, const std::string& backend,
                        const py::object& out) {
    const FusionSpec spec = spec_of(method, wavelet, levels, mode, base_rule, detail_rule);
    Frames frames = to_frames(frames_in, "frames");
    const int S = sensors, n = int(frames.arrays.size());
    if (S < 1 || n % S != 0)
        throw Error(ErrorKind::InvalidArgument, "sensors " + std::to_string(S) + ": " + std::to_string(n) +
                                                    " frames do not split into that many sensors");
    const int K = n / S;
    validate(spec, frames.height, frames.width, frames.channels, K);
    py::array_t<float> result = fused_array(out, S, frames.height, frames.width, frames.channels, frames.gray);
    float* const into = result.mutable_data();
    Context* context = open_backend(backend);
    if (!context) {
        const std::vector<ImageD> images = frames.images();
        for (int s = 0; s < S; ++s) {
            ImageD fused;
            {
                py::gil_scoped_release unlocked;
                fused = fuse_reference(std::span(images).subspan(std::size_t(s * K), std::size_t(K)), spec);
            }
            put(into, s, fused);
        }
        return result;
    }
    PlanConfig c;
    c.fusion = spec;
    c.height = frames.height, c.width = frames.width, c.channels = frames.channels;
    c.frames = K;
    c.sensors = S;
    c.input = frames.type;
    c.metrics = {};
    const std::vector<FrameView> views = frames.views();
    {
        py::gil_scoped_release unlocked;
        with_plan(c, [&](Plan& plan) {
            plan.run(views);
            for (int s = 0; s < S; ++s) put(into, s, plan.fused(s));
        });
    }
    return result;
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

}  // namespace

void def_fusion(py::module_& m) {
    m.def("fuse", &fuse, py::arg("frames"), py::arg("sensors") = 1, py::arg("method") = "wavelet",
          py::arg("wavelet") = "bior4.4", py::arg("levels") = py::none(), py::arg("mode") = "periodization",
          py::arg("base_rule") = "mean", py::arg("detail_rule") = "max-abs", py::arg("backend") = "auto",
          py::arg("out") = py::none(),
          "S x K frames (sensor-major; uint8 scaled by 1/255, float32 or float64; (H, W) or (H, W, C)) fused "
          "into float32 (S, H, W[, C]).");
    m.def("metrics", &metrics, py::arg("image"), py::arg("background") = py::none(), py::arg("backend") = "auto",
          "Sharpness, RMS contrast and, with a background, the mean absolute difference from it.");
    m.def("max_levels", [](const std::string& method, const std::string& wavelet, int height, int width) {
        return max_levels(parse_method(method), parse_wavelet(wavelet), height, width);
    }, py::arg("method"), py::arg("wavelet"), py::arg("height"), py::arg("width"),
          "The deepest level count the method takes at this size (0: it has none).");
}

}  // namespace vkfuse::python

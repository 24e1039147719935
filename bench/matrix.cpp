#include "matrix.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>

#include "core/method_table.hpp"
#include "inputs.hpp"
#include "options.hpp"
#include "vk/plan/method_recorders.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::bench {

namespace {

// A cartesian block of the matrix.
struct Slice {
    std::vector<MethodVariant> methods;
    std::vector<Backend> backends;
    std::vector<Size> sizes;
    std::vector<int> frames;
    std::vector<int> sensors;
    // fp16 storage is never in a default; --full and --quick add it (Vulkan only).
    std::vector<Precision> precisions{Precision::Fp32};
};

constexpr Size kQvga{320, 240}, kVga{640, 480};
constexpr Size kQuickSize{160, 120};  // small enough that --quick takes seconds on lavapipe

// Default: the side-by-side of every method at QVGA and VGA; batching at
// QVGA on the GPU for the cheapest method and the multi-scale ones; K = 2, 5
// for the multi-scale ones. The CPU reference has no batching (its S-sensor
// time is S times its S = 1 time), so it is not run at S > 1 by default.
// About 2 minutes on an idle 2-core lavapipe host.
std::vector<Slice> default_slices() {
    const auto all = all_method_variants();
    const std::vector<Backend> both{Backend::Cpu, Backend::Vulkan};
    return {{all, both, {kQvga, kVga}, {3}, {1}},
            {batched_methods(), {Backend::Vulkan}, {kQvga}, {3}, {8, 64}},
            {multiscale_methods(), both, {kQvga}, {2, 5}, {1}}};
}

std::vector<Slice> scope_slices(Scope scope) {
    const std::vector<Backend> both{Backend::Cpu, Backend::Vulkan};
    switch (scope) {
        case Scope::Quick:
            return {{every_method(), both, {kQuickSize}, {3}, {1, 2}, all_precisions()}};
        case Scope::Full:
            return {{all_method_variants(), both, all_sizes(), all_frame_counts(), all_sensor_counts(), all_precisions()}};
        case Scope::Default: break;
    }
    return default_slices();
}

bool any_axis_filter(const Options& o) {
    return !o.methods.empty() || !o.wavelets.empty() || !o.backends.empty() || !o.sizes.empty() || !o.frames.empty() ||
           !o.sensors.empty() || !o.precisions.empty();
}

template <class T>
bool contains(const std::vector<T>& v, const T& x) {
    return std::find(v.begin(), v.end(), x) != v.end();
}

// --method and --wavelet: a wavelet filter alone means "wavelet cells of these families".
std::vector<MethodVariant> filter_methods(const Options& o, const std::vector<MethodVariant>& scope) {
    std::vector<Method> methods = o.methods;
    if (methods.empty() && !o.wavelets.empty())
        for (const core::MethodInfo& m : core::method_table())
            if (m.uses_wavelet) methods.push_back(m.method);
    std::vector<MethodVariant> out;
    for (const auto& m : all_method_variants()) {
        const bool method_ok = methods.empty() ? contains(scope, m) : contains(methods, m.method);
        const bool wavelet_ok = !m.has_wavelet() || o.wavelets.empty() || contains(o.wavelets, m.wavelet);
        if (method_ok && wavelet_ok) out.push_back(m);
    }
    return out;
}

template <class T>
void replace_if_given(std::vector<T>& axis, const std::vector<T>& filter) {
    if (!filter.empty()) axis = filter;
}

// With an axis option, the default scope becomes one block: the given axes
// with QVGA, K = 3, S = 1, every method and both backends for the others.
std::vector<Slice> filtered_slices(const Options& o) {
    std::vector<Slice> slices = scope_slices(o.scope);
    if (o.scope == Scope::Default && any_axis_filter(o))
        slices = {{all_method_variants(), {Backend::Cpu, Backend::Vulkan}, {kQvga}, {3}, {1}}};
    for (auto& s : slices) {
        s.methods = filter_methods(o, s.methods);
        replace_if_given(s.backends, o.backends);
        replace_if_given(s.sizes, o.sizes);
        replace_if_given(s.frames, o.frames);
        replace_if_given(s.sensors, o.sensors);
        replace_if_given(s.precisions, o.precisions);
    }
    return slices;
}

std::vector<int> level_counts(const Options& o, Method m) {
    if (core::method_info(m).default_levels == 0) return {0};
    if (!o.levels.empty()) return o.levels;
    FusionSpec spec;
    spec.method = m;
    return {spec.effective_levels()};
}

std::string gib(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", bytes / (1024.0 * 1024.0 * 1024.0));
    return text;
}

// Why a cell cannot run, or "" when it can.
std::string skip_reason(const Cell& c, double budget) {
    try {
        validate(c.fusion(), c.size.height, c.size.width, 3, c.frames);
    } catch (const Error& e) {
        return e.what();
    }
    const double need = estimated_bytes(c);
    if (need > budget) return "needs ~" + gib(need) + " GiB (limit " + gib(budget) + " GiB)";
    return "";
}

void add_slice(const Options& o, const Slice& s, double budget, std::vector<Cell>& out) {
    for (const auto& m : s.methods)
        for (int levels : level_counts(o, m.method))
            for (Backend b : s.backends)
                for (Precision p : s.precisions)
                    for (Size size : s.sizes)
                        for (int k : s.frames)
                            for (int sensors : s.sensors) {
                                const int exact_k = core::method_info(m.method).exact_frames;
                                if (exact_k != 0 && k != exact_k) continue;  // channel-sum: K = 3 only
                                if (b == Backend::Cpu && p != Precision::Fp32) continue;  // the reference is double
                                Cell c{m, levels, b, p, size, k, sensors, ""};
                                c.skip = skip_reason(c, budget);
                                out.push_back(c);
                            }
}

auto order_key(const Cell& c) {
    const auto methods = all_method_variants();
    const auto method_index = std::find(methods.begin(), methods.end(), c.method) - methods.begin();
    return std::make_tuple(c.size.pixels(), c.size.width, c.frames, c.sensors, method_index, c.levels, c.backend,
                           c.precision);
}

}  // namespace

std::vector<Cell> build_matrix(const Options& o, double budget) {
    std::vector<Cell> cells;
    for (const auto& slice : filtered_slices(o)) add_slice(o, slice, budget, cells);
    std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return order_key(a) < order_key(b); });
    cells.erase(std::unique(cells.begin(), cells.end(),
                            [](const Cell& a, const Cell& b) { return order_key(a) == order_key(b); }),
                cells.end());
    if (cells.empty())
        throw UsageError("no benchmark cell matches these options (channel-sum needs --frames 3; fp16 is Vulkan only)");
    return cells;
}

namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
constexpr double kProcessBytes = 0.25 * kGiB;  // the process itself: Vulkan driver, LLVM (lavapipe), Python peer

}  // namespace

double estimated_bytes(const Cell& c) {
    const double frame = double(c.size.width) * c.size.height * 3 * sizeof(float);
    const double inputs = frame * c.frames * c.sensors;
    const double outputs = frame * c.sensors;
    const double scenes = std::min(c.sensors, kMaxScenes);
    const double checked = std::min(c.sensors, 4);
    // One reference computation at its peak: K frames in double, their
    // transforms (about 1.5 times their size) and the fused result.
    const double reference = 2 * frame * (2.5 * c.frames + 2);
    // Host: generated frames and backgrounds, one reference computation, the
    // checked sensors' reference results kept (double).
    const double host = kProcessBytes + frame * scenes * (c.frames + 1) + reference + 2 * frame * checked;
    // The CPU backend: its own computation, its backgrounds and kept results in double.
    if (c.backend == Backend::Cpu) return host + reference + 2 * frame * (scenes + checked);
    // Upload + planar input, the method's intermediates (its Vulkan row) and
    // fused planes, readback + backgrounds, and the fused images Plan::fused()
    // keeps on the host.
    const vk::MethodRecorder& m = vk::method_recorder(c.method.method);
    return host + 2 * inputs + m.floats_per_input * inputs + (m.floats_per_output + 1) * outputs + 3 * outputs;
}

double memory_budget(double limit_gib) {
    if (limit_gib > 0) return limit_gib * kGiB;
    std::ifstream meminfo("/proc/meminfo");
    std::string line;
    while (std::getline(meminfo, line)) {
        std::istringstream fields(line);
        std::string key;
        double kib = 0;
        if (fields >> key >> kib && key == "MemAvailable:") return 0.8 * kib * 1024.0;
    }
    return 4 * kGiB;
}

}  // namespace vkfuse::bench

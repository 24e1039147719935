#include "axes.hpp"

#include <cctype>
#include <charconv>

#include "core/method_table.hpp"
#include "options.hpp"
#include "vk/plan/method_recorders.hpp"

namespace vkfuse::bench {
namespace {

struct NamedSize {
    std::string_view name;
    Size size;
};

// The resolutions the benchmark knows by name (issue 4's matrix).
constexpr NamedSize kNamedSizes[] = {
    {"QVGA", {320, 240}}, {"VGA", {640, 480}}, {"1080p", {1920, 1080}}, {"4096^2", {4096, 4096}}};

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool parse_dimension(std::string_view text, int& out) {
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, out);
    return ec == std::errc() && ptr == end && out >= 1 && out <= 65536;
}

}  // namespace

std::string_view to_string(Backend b) { return b == Backend::Cpu ? "cpu" : "vulkan"; }

bool MethodVariant::has_wavelet() const { return core::method_info(method).uses_wavelet; }

std::string label(const MethodVariant& m) {
    std::string out(vkfuse::to_string(m.method));
    if (m.has_wavelet()) out += "/" + std::string(vkfuse::to_string(m.wavelet));
    return out;
}

std::string short_size_name(Size s) {
    for (const auto& n : kNamedSizes)
        if (n.size == s) return std::string(n.name);
    return std::to_string(s.width) + "x" + std::to_string(s.height);
}

std::string size_name(Size s) {
    const std::string dims = std::to_string(s.width) + "x" + std::to_string(s.height);
    const std::string name = short_size_name(s);
    return name == dims ? dims : dims + " (" + name + ")";
}

Backend parse_backend(std::string_view option, std::string_view text) {
    if (text == "cpu") return Backend::Cpu;
    if (text == "vulkan") return Backend::Vulkan;
    throw UsageError(std::string(option) + ": unknown backend \"" + std::string(text) + "\" (expected cpu, vulkan)");
}

Precision parse_precision(std::string_view option, std::string_view text) {
    if (text == "fp32") return Precision::Fp32;
    if (text == "fp16") return Precision::Fp16Storage;
    throw UsageError(std::string(option) + ": unknown precision \"" + std::string(text) + "\" (expected fp32, fp16)");
}

Size parse_size(std::string_view option, std::string_view text) {
    const std::string name = lower(text);
    for (const auto& n : kNamedSizes)
        if (name == lower(n.name) || (name == "4k" && n.size.width == 4096)) return n.size;
    const auto x = name.find('x');
    Size s;
    if (x == std::string::npos || !parse_dimension(std::string_view(name).substr(0, x), s.width) ||
        !parse_dimension(std::string_view(name).substr(x + 1), s.height))
        throw UsageError(std::string(option) + ": bad size \"" + std::string(text) +
                         "\" (expected WxH, e.g. 320x240, or qvga, vga, 1080p, 4k)");
    return s;
}

std::vector<MethodVariant> all_method_variants() {
    std::vector<MethodVariant> out;
    for (const core::MethodInfo& m : core::method_table()) {
        if (!m.uses_wavelet) {
            out.push_back({m.method, Wavelet::Bior44});
            continue;
        }
        for (Wavelet w : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44}) out.push_back({m.method, w});
    }
    return out;
}

std::vector<MethodVariant> every_method() {
    std::vector<MethodVariant> out;
    for (const core::MethodInfo& m : core::method_table()) out.push_back({m.method, Wavelet::Bior44});
    return out;
}

std::vector<MethodVariant> multiscale_methods() {
    std::vector<MethodVariant> out;
    for (const core::MethodInfo& m : core::method_table())
        if (vk::method_recorder(m.method).shape == vk::GraphShape::Multiscale) out.push_back({m.method, Wavelet::Bior44});
    return out;
}

std::vector<MethodVariant> batched_methods() {
    std::vector<MethodVariant> out;
    for (const core::MethodInfo& m : core::method_table())
        if (vk::method_recorder(m.method).shape == vk::GraphShape::Pointwise && m.exact_frames == 0)
            out.push_back({m.method, Wavelet::Bior44});
    const auto multiscale = multiscale_methods();
    out.insert(out.end(), multiscale.begin(), multiscale.end());
    return out;
}

const std::vector<Size>& all_sizes() {
    static const std::vector<Size> sizes = [] {
        std::vector<Size> out;
        for (const auto& n : kNamedSizes) out.push_back(n.size);
        return out;
    }();
    return sizes;
}

const std::vector<int>& all_frame_counts() {
    static const std::vector<int> k{2, 3, 5};
    return k;
}

const std::vector<int>& all_sensor_counts() {
    static const std::vector<int> s{1, 8, 64};
    return s;
}

const std::vector<Precision>& all_precisions() {
    static const std::vector<Precision> p{Precision::Fp32, Precision::Fp16Storage};
    return p;
}

}  // namespace vkfuse::bench

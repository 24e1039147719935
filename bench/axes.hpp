// The axes of the benchmark matrix and their names on the command line.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::bench {

enum class Backend { Cpu, Vulkan };

// The plan's storage precision (vkfuse/vk/plan.hpp): fp32, or fp16 storage
// (docs/spec.md's optional reduced-precision mode), a Vulkan-only axis that is
// never in the default subset and is reported against the same reference.
using vkfuse::Precision;

// A fusion method, and for a method that uses one (Method::Wavelet) the wavelet family.
struct MethodVariant {
    Method method = Method::Wavelet;
    Wavelet wavelet = Wavelet::Bior44;  // ignored unless has_wavelet()
    bool operator==(const MethodVariant&) const = default;
    bool has_wavelet() const;  // the method's row uses a wavelet (core/method_table.hpp)
};

struct Size {
    int width = 0;
    int height = 0;
    bool operator==(const Size&) const = default;
    double pixels() const { return double(width) * height; }
};

std::string_view to_string(Backend);
// "channel-sum", "laplacian", "wavelet/bior4.4".
std::string label(const MethodVariant&);
// "320x240", with the common name where there is one: "QVGA".
std::string size_name(Size);
std::string short_size_name(Size);  // "QVGA", "VGA", "1080p", "4096^2", else "WxH"

// Parsers throw UsageError (options.hpp) naming the option and the bad value.
Backend parse_backend(std::string_view option, std::string_view text);
Precision parse_precision(std::string_view option, std::string_view text);  // fp32, fp16
Size parse_size(std::string_view option, std::string_view text);  // "WxH" or qvga, vga, 1080p, 4k

// Every value each axis can take, in the order the matrix walks them.
std::vector<MethodVariant> all_method_variants();
// Every method once, at its default wavelet where it takes one.
std::vector<MethodVariant> every_method();
// The batching cells' methods, from the Vulkan rows: the multi-scale ones,
// after the pointwise ones that take any number of frames (the cheapest).
std::vector<MethodVariant> batched_methods();
// The multi-scale methods alone (their own rows say so).
std::vector<MethodVariant> multiscale_methods();
const std::vector<Size>& all_sizes();
const std::vector<int>& all_frame_counts();
const std::vector<int>& all_sensor_counts();
const std::vector<Precision>& all_precisions();

}  // namespace vkfuse::bench

// vkfuse/core/metrics.hpp - the paper's image quality metrics (docs/spec.md, "Metrics").
#pragma once
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace vkfuse {

// One metric. Its name (to_string) is also its key in every JSON output.
enum class Metric : std::uint8_t {
    Sharpness,       // "sharpness": mean gradient magnitude of luma (numpy.gradient)
    Contrast,        // "contrast": RMS contrast, the population std of luma
    BackgroundDiff,  // "background_diff": mean |I - B| over pixels and channels
};
inline constexpr Metric kAllMetrics[] = {Metric::Sharpness, Metric::Contrast, Metric::BackgroundDiff};
std::string_view to_string(Metric metric);

// Which metrics to compute. A plan or a run computes only these: a metric it
// was not asked for costs nothing and reads NaN (background_diff: absent).
class MetricSet {
public:
    constexpr MetricSet() = default;  // none
    constexpr MetricSet(std::initializer_list<Metric> metrics) {
        for (Metric m : metrics) bits_ |= bit(m);
    }
    static constexpr MetricSet all() { return {Metric::Sharpness, Metric::Contrast, Metric::BackgroundDiff}; }

    constexpr bool has(Metric m) const { return (bits_ & bit(m)) != 0; }
    constexpr bool empty() const { return bits_ == 0; }
    constexpr MetricSet with(Metric m, bool on = true) const {
        MetricSet s = *this;
        s.bits_ = on ? s.bits_ | bit(m) : s.bits_ & ~bit(m);
        return s;
    }
    constexpr bool operator==(const MetricSet&) const = default;

    // "sharpness,contrast": the names in kAllMetrics order, comma-separated
    // ("" for none).
    std::string to_string() const;
    // The inverse of to_string (any order, no repeats, at least one name);
    // nullopt for anything else.
    static std::optional<MetricSet> parse(std::string_view list);

private:
    static constexpr std::uint8_t bit(Metric m) { return std::uint8_t(1u << unsigned(m)); }
    std::uint8_t bits_ = 0;
};

struct Metrics {
    double sharpness = 0;   // NaN when not asked for
    double contrast = 0;    // NaN when not asked for
    std::optional<double> background_diff;  // absent when not asked for or without a background
};

}  // namespace vkfuse

// Metric names and metric lists (vkfuse/core/metrics.hpp).
#include <string>

#include "vkfuse/core/metrics.hpp"

namespace vkfuse {

std::string_view to_string(Metric metric) {
    // No default: a Metric without its name here fails to compile (-Wswitch).
    switch (metric) {
        case Metric::Sharpness: return "sharpness";
        case Metric::Contrast: return "contrast";
        case Metric::BackgroundDiff: return "background_diff";
    }
    return "?";
}

std::string MetricSet::to_string() const {
    std::string out;
    for (Metric m : kAllMetrics)
        if (has(m)) out += (out.empty() ? "" : ",") + std::string(vkfuse::to_string(m));
    return out;
}

std::optional<MetricSet> MetricSet::parse(std::string_view list) {
    MetricSet set;
    while (true) {
        const std::size_t comma = list.find(',');
        const std::string_view name = list.substr(0, comma);
        bool known = false;
        for (Metric m : kAllMetrics)
            if (name == vkfuse::to_string(m)) {
                if (set.has(m)) return std::nullopt;
                set = set.with(m);
                known = true;
            }
        if (!known) return std::nullopt;
        if (comma == std::string_view::npos) return set;
        list.remove_prefix(comma + 1);
    }
}

}  // namespace vkfuse

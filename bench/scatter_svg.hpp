// scatter_svg.hpp - a plot of a rate or time against an error (log x), one
// colour per series, for the bench modes that trade one for the other
// (--scenes: skipping's time; --windows: a sliding window's fused rate).
#pragma once
#include <string>
#include <vector>

namespace vkfuse::bench {

struct ScatterPoint {
    double error = 0;    // x, on a log axis from 1e-6 to 1 (0 sits on the left edge)
    double value = 0;    // y, linear from 0
    std::string series;  // one colour each, named in the key
    std::string title;   // shown on hovering the point
};

struct ScatterLabels {
    std::string title, x, y;
};

// Writes the plot atomically; throws vkfuse::Error(Io) on failure.
void write_scatter_svg(const std::string& path, const std::vector<ScatterPoint>& points, const ScatterLabels& labels);

}  // namespace vkfuse::bench

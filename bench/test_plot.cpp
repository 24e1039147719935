// The time-against-error plot (report_svg.cpp): every measured cell and each
// workload's peers drawn, no two point labels overlapping however crowded the
// points, and every workload a row of the table under the plot.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "report.hpp"

namespace vkfuse::bench {
namespace {

CellResult measured(Method m, int sensors, Backend backend, double ms, double error) {
    CellResult r;
    r.cell.method.method = m;
    r.cell.levels = m == Method::Laplacian ? 4 : 0;
    r.cell.size = {320, 240};
    r.cell.sensors = sensors;
    r.cell.backend = backend;
    r.timing.median_ms = ms;
    r.error.max_abs = error;
    return r;
}

PeerResult peer(double ms, double error) {
    PeerResult p;
    p.name = "peer";
    p.per_sensor.median_ms = ms;
    p.error.max_abs = error;
    return p;
}

std::string plot_of(const std::vector<CellResult>& results) {
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("vkfuse_test_plot_" + std::to_string(::getpid()) + ".svg")).string();
    write_plot(path, results, "test device");
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::filesystem::remove(path);
    return text.str();
}

// The plot's own estimate of a 9 px label's box, from its x, y (baseline) and text.
struct LabelBox {
    double x0, y0, x1, y1;
};

TEST(BenchPlot, CrowdedPointsGetLabelsThatNeverOverlap) {
    // Three methods at S = 1, 8, 64 and both backends, nearly all at one
    // time and one error: the default run's pile-up, made worse.
    std::vector<CellResult> results;
    for (Method m : {Method::ChannelSum, Method::Brovey, Method::Laplacian})
        for (int s : {1, 8, 64})
            for (Backend b : {Backend::Vulkan, Backend::Cpu}) {
                CellResult r = measured(m, s, b, 1.0 * s + (b == Backend::Cpu ? 0.01 : 0), 1e-6);
                r.peer = peer(1.1, 2e-6);
                r.cpp_peer = peer(0.9, 2e-6);
                results.push_back(r);
            }
    const std::string svg = plot_of(results);

    const std::regex label_re("<text x=\"([0-9.-]+)\" y=\"([0-9.-]+)\" class=\"point-label\"[^>]*>([^<]*)</text>");
    std::vector<LabelBox> boxes;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label_re); it != std::sregex_iterator(); ++it) {
        const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
        const double w = 5.6 * double((*it)[3].length());
        boxes.push_back({x, y - 7.5, x + w, y + 1.5});
    }
    ASSERT_GE(boxes.size(), 3u) << svg;
    for (std::size_t i = 0; i < boxes.size(); ++i)
        for (std::size_t j = i + 1; j < boxes.size(); ++j) {
            const LabelBox &a = boxes[i], &b = boxes[j];
            EXPECT_FALSE(a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1) << "labels " << i << " and " << j;
        }

    // 18 cells, and per method one Python and one C++ peer point (a peer runs
    // one sensor: the same point at every S).
    std::size_t markers = 0;
    for (std::size_t at = 0; (at = svg.find("stroke-width=\"0.6\"", at)) != std::string::npos; ++at) ++markers;
    markers -= 5;  // the legend's five kinds
    EXPECT_EQ(markers, 18u + 3 * 2);
    const std::size_t labelled = boxes.size();
    const std::size_t crowded = svg.find("too crowded to number") != std::string::npos;
    EXPECT_TRUE(labelled == markers || crowded) << labelled << " of " << markers;

    // One table row per workload (method, size, K, S): 9, numbered 1..9.
    for (int row = 1; row <= 9; ++row) EXPECT_NE(svg.find(">" + std::to_string(row) + "</text>"), std::string::npos) << row;
    EXPECT_NE(svg.find("laplacian L4"), std::string::npos);
    EXPECT_NE(svg.find("opencv c++ peer"), std::string::npos);
}

}  // namespace
}  // namespace vkfuse::bench

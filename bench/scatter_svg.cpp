#include "scatter_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/atomic_write.hpp"

namespace vkfuse::bench {

// Escapes what SVG text cannot hold as is.
static std::string xml_text(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '&') out += "&amp;";
        else out += c;
    }
    return out;
}

void write_scatter_svg(const std::string& path, const std::vector<ScatterPoint>& points, const ScatterLabels& labels) {
    constexpr double kW = 640, kH = 400, kL = 70, kR = 150, kT = 40, kB = 50, kMinErr = 1e-6, kMaxErr = 1.0;
    const char* colours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666"};
    constexpr std::size_t kColours = sizeof colours / sizeof colours[0];
    double top = 1e-9;
    for (const ScatterPoint& p : points) top = std::max(top, p.value);
    auto x = [&](double e) {
        return kL + (kW - kL - kR) * (std::log10(std::clamp(e, kMinErr, kMaxErr)) - std::log10(kMinErr)) /
                        (std::log10(kMaxErr) - std::log10(kMinErr));
    };
    auto y = [&](double v) { return kH - kB - (kH - kT - kB) * v / (top * 1.05); };
    std::string svg =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"400\" font-family=\"sans-serif\" font-size=\"12\">\n";
    svg += "<text x=\"70\" y=\"16\">" + xml_text(labels.title) + "</text>\n";
    svg += "<text x=\"200\" y=\"390\">" + xml_text(labels.x) + " (log, 1e-6 .. 1)</text>\n";
    svg += "<text x=\"5\" y=\"34\">" + xml_text(labels.y) + "</text>\n";
    char axis[160];
    std::snprintf(axis, sizeof axis, "<text x=\"5\" y=\"%.1f\">%.3g</text>\n", y(top) + 4, top);
    svg += axis;
    svg += "<rect x=\"70\" y=\"40\" width=\"420\" height=\"310\" fill=\"none\" stroke=\"black\"/>\n";
    std::vector<std::string> names;
    for (const ScatterPoint& p : points) {
        auto it = std::find(names.begin(), names.end(), p.series);
        if (it == names.end()) it = names.insert(names.end(), p.series);
        char dot[160];
        std::snprintf(dot, sizeof dot, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\"><title>", x(p.error),
                      y(p.value), colours[std::size_t(it - names.begin()) % kColours]);
        svg += dot + xml_text(p.title) + "</title></circle>\n";
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
        char key[120];
        std::snprintf(key, sizeof key, "<text x=\"500\" y=\"%d\" fill=\"%s\">", 60 + 18 * int(i), colours[i % kColours]);
        svg += key + xml_text(names[i]) + "</text>\n";
    }
    svg += "</svg>\n";
    io::write_atomically(path, [&](std::FILE* f) { io::write_all(f, svg, path); });
}

}  // namespace vkfuse::bench

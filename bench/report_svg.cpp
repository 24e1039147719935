#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "core/method_table.hpp"
#include "io/atomic_write.hpp"

namespace vkfuse::bench {
namespace {

// An error of exactly 0 (the reference against itself) has no place on a log
// axis; it is drawn at this floor and the legend says so.
constexpr double kErrorFloor = 1e-10;

enum class Marker { Vulkan, VulkanFp16, Cpu, Peer };

struct Point {
    double ms;      // per sensor-cycle
    double error;   // max abs error of the fused image
    std::string method;
    Marker marker;
    std::string label;
};

struct Frame {  // the plotting area and its log-log mapping
    double left = 80, top = 50, width = 640, height = 480;
    double x0, x1, y0, y1;  // decades shown
    double x(double ms) const { return left + (std::log10(ms) - x0) / (x1 - x0) * width; }
    double y(double err) const { return top + height - (std::log10(err) - y0) / (y1 - y0) * height; }
};

// A method's colour is its row's (core/method_table.hpp); the wavelet's cells
// are told apart by wavelet, bior4.4 keeping the row's colour.
std::string colour(const std::string& label) {
    static const std::map<std::string, const char*> wavelets{
        {"haar", "#d62728"}, {"db2", "#9467bd"}, {"bior2.2", "#8c564b"}};
    const std::size_t slash = label.find('/');
    if (slash != std::string::npos)
        if (auto it = wavelets.find(label.substr(slash + 1)); it != wavelets.end()) return it->second;
    return std::string(core::method_info(parse_method(label.substr(0, slash))).plot_colour);
}

std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", v);
    return text;
}

std::string point_label(const Cell& c) {
    return short_size_name(c.size) + " K" + std::to_string(c.frames) + " S" + std::to_string(c.sensors);
}

Marker marker_of(const Cell& c) {
    if (c.backend == Backend::Cpu) return Marker::Cpu;
    return c.precision == Precision::Fp16Storage ? Marker::VulkanFp16 : Marker::Vulkan;
}

std::vector<Point> collect(const std::vector<CellResult>& results) {
    std::vector<Point> pts;
    for (std::size_t i = 0; i < results.size(); ++i) {
        const auto& r = results[i];
        if (r.measured())
            pts.push_back({r.timing.median_ms / r.cell.sensors, std::max(r.error.max_abs, kErrorFloor), label(r.cell.method),
                           marker_of(r.cell), point_label(r.cell)});
        const bool first_of_workload = i == 0 || !results[i - 1].cell.same_workload(r.cell);
        if (first_of_workload && r.peer && r.peer->failure.empty())
            pts.push_back({r.peer->per_sensor.median_ms, std::max(r.peer->error.max_abs, kErrorFloor), label(r.cell.method),
                           Marker::Peer, point_label(r.cell)});
    }
    return pts;
}

Frame fit(const std::vector<Point>& pts) {
    Frame f;
    double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
    for (const auto& p : pts) {
        xmin = std::min(xmin, p.ms);
        xmax = std::max(xmax, p.ms);
        ymin = std::min(ymin, p.error);
        ymax = std::max(ymax, p.error);
    }
    f.x0 = std::floor(std::log10(xmin));
    f.x1 = std::max(f.x0 + 1, std::ceil(std::log10(xmax)));
    f.y0 = std::floor(std::log10(ymin));
    f.y1 = std::max(f.y0 + 1, std::ceil(std::log10(ymax)));
    return f;
}

std::string marker_svg(Marker m, double x, double y, const char* fill) {
    const std::string style = std::string(" fill=\"") + fill + "\" stroke=\"#000\" stroke-width=\"0.6\"/>\n";
    switch (m) {
        case Marker::Vulkan: return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"5\"" + style;
        case Marker::VulkanFp16:  // a diamond: the same device, half the storage
            return "<polygon points=\"" + num(x) + "," + num(y - 6) + " " + num(x + 6) + "," + num(y) + " " + num(x) + "," +
                   num(y + 6) + " " + num(x - 6) + "," + num(y) + "\"" + style;
        case Marker::Cpu:
            return "<rect x=\"" + num(x - 4.5) + "\" y=\"" + num(y - 4.5) + "\" width=\"9\" height=\"9\"" + style;
        case Marker::Peer: break;
    }
    return "<polygon points=\"" + num(x) + "," + num(y - 6) + " " + num(x - 5.5) + "," + num(y + 4) + " " + num(x + 5.5) +
           "," + num(y + 4) + "\"" + style;
}

std::string xml_escaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string text_svg(double x, double y, const std::string& text, const char* extra = "") {
    return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\"" + extra + ">" + xml_escaped(text) + "</text>\n";
}

std::string axes_svg(const Frame& f) {
    std::string s;
    for (double d = f.x0; d <= f.x1; ++d) {
        const double x = f.x(std::pow(10.0, d));
        s += "<line x1=\"" + num(x) + "\" y1=\"" + num(f.top) + "\" x2=\"" + num(x) + "\" y2=\"" + num(f.top + f.height) +
             "\" stroke=\"#ddd\"/>\n";
        s += text_svg(x, f.top + f.height + 18, "1e" + std::to_string(int(d)), " text-anchor=\"middle\"");
    }
    for (double d = f.y0; d <= f.y1; ++d) {
        const double y = f.y(std::pow(10.0, d));
        s += "<line x1=\"" + num(f.left) + "\" y1=\"" + num(y) + "\" x2=\"" + num(f.left + f.width) + "\" y2=\"" + num(y) +
             "\" stroke=\"#ddd\"/>\n";
        s += text_svg(f.left - 8, y + 4, "1e" + std::to_string(int(d)), " text-anchor=\"end\"");
    }
    // The frame last, so the grid does not paint over it.
    s += "<rect x=\"" + num(f.left) + "\" y=\"" + num(f.top) + "\" width=\"" + num(f.width) + "\" height=\"" +
         num(f.height) + "\" fill=\"none\" stroke=\"#000\"/>\n";
    s += text_svg(f.left + f.width / 2, f.top + f.height + 40, "time per sensor-cycle (ms, fusion + 3 metrics + readback)",
                  " text-anchor=\"middle\"");
    s += text_svg(20, f.top + f.height / 2, "max abs error of the fused image vs the double reference",
                  (" text-anchor=\"middle\" transform=\"rotate(-90 20 " + num(f.top + f.height / 2) + ")\"").c_str());
    return s;
}

std::string legend_svg(const Frame& f, const std::vector<Point>& pts) {
    double y = f.top + 10;
    const double x = f.left + f.width + 20;
    std::string s;
    std::vector<std::string> methods;
    for (const auto& p : pts)
        if (std::find(methods.begin(), methods.end(), p.method) == methods.end()) methods.push_back(p.method);
    for (const auto& m : methods) {
        s += "<rect x=\"" + num(x) + "\" y=\"" + num(y - 9) + "\" width=\"12\" height=\"12\" fill=\"" + colour(m) + "\"/>\n";
        s += text_svg(x + 18, y + 2, m);
        y += 18;
    }
    y += 10;
    const std::pair<Marker, const char*> kinds[] = {
        {Marker::Vulkan, "vulkan fp32"}, {Marker::VulkanFp16, "vulkan fp16 storage"}, {Marker::Cpu, "cpu reference (double)"}, {Marker::Peer, "python peer (float32)"}};
    for (const auto& [m, name] : kinds) {
        s += marker_svg(m, x + 6, y - 3, "#fff");
        s += text_svg(x + 18, y + 2, name);
        y += 18;
    }
    s += text_svg(x, y + 12, "error 0 (the reference itself)", " font-size=\"10\"");
    s += text_svg(x, y + 25, "is drawn at 1e-10", " font-size=\"10\"");
    return s;
}

}  // namespace

void write_plot(const std::string& path, const std::vector<CellResult>& results, const std::string& device) {
    const std::vector<Point> pts = collect(results);
    std::string svg =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1000\" height=\"600\" font-family=\"sans-serif\" "
        "font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
    svg += text_svg(80, 28, "vkfuse-bench: time against error (" + device + ")", " font-size=\"15\"");
    if (pts.empty()) {
        svg += text_svg(80, 80, "no measured cell");
    } else {
        const Frame f = fit(pts);
        svg += axes_svg(f) + legend_svg(f, pts);
        for (const auto& p : pts) {
            svg += marker_svg(p.marker, f.x(p.ms), f.y(p.error), colour(p.method).c_str());
            svg += text_svg(f.x(p.ms) + 7, f.y(p.error) - 6, p.label, " font-size=\"9\" fill=\"#444\"");
        }
    }
    svg += "</svg>\n";
    io::write_atomically(path, [&](std::FILE* out) { io::write_all(out, svg, path); });
}

}  // namespace vkfuse::bench

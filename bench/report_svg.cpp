#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

#include "core/method_table.hpp"
#include "io/atomic_write.hpp"

namespace vkfuse::bench {
namespace {

// An error of exactly 0 (the reference against itself) has no place on a log
// axis; it is drawn at this floor and the legend says so.
constexpr double kErrorFloor = 1e-10;

enum class Marker { Vulkan, VulkanFp16, Cpu, Peer, CppPeer };

// One workload (method, levels, size, K, S): a row of the table under the
// plot, numbered; its points carry the number.
struct Workload {
    std::string method;  // "wavelet/bior4.4 L3"
    std::string size;
    int frames = 0, sensors = 0;
    // Per marker: ms per sensor-cycle and the fused image's max abs error.
    std::map<Marker, std::pair<double, double>> cells;
};

struct Point {
    double ms;      // per sensor-cycle
    double error;   // max abs error of the fused image
    std::string method;
    Marker marker;
    std::size_t workload;  // index into the table's rows
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

Marker marker_of(const Cell& c) {
    if (c.backend == Backend::Cpu) return Marker::Cpu;
    return c.precision == Precision::Fp16Storage ? Marker::VulkanFp16 : Marker::Vulkan;
}

std::string method_name(const Cell& c) {
    return label(c.method) + (c.levels > 0 ? " L" + std::to_string(c.levels) : "");
}

// Every measured cell, each workload's peers once: a peer runs one sensor, so
// its point is the same at every S and is drawn with the first workload's
// number.
std::pair<std::vector<Point>, std::vector<Workload>> collect(const std::vector<CellResult>& results) {
    std::vector<Point> pts;
    std::vector<Workload> rows;
    // A row per (method, size, K, S); a peer's point per (method, size, K).
    std::map<std::tuple<std::string, std::string, int, int>, std::size_t> row_of;
    std::set<std::tuple<std::string, std::string, int, Marker>> peers_drawn;
    const auto add = [&](const Cell& c, Marker m, double ms, double error) {
        Workload w{method_name(c), short_size_name(c.size), c.frames, c.sensors, {}};
        auto [it, fresh] = row_of.emplace(std::tuple(w.method, w.size, w.frames, w.sensors), rows.size());
        if (fresh) rows.push_back(w);
        rows[it->second].cells[m] = {ms, error};
        const bool peer = m == Marker::Peer || m == Marker::CppPeer;
        if (peer && !peers_drawn.emplace(w.method, w.size, w.frames, m).second) return;
        pts.push_back({ms, std::max(error, kErrorFloor), label(c.method), m, it->second});
    };
    for (std::size_t i = 0; i < results.size(); ++i) {
        const auto& r = results[i];
        if (r.measured()) add(r.cell, marker_of(r.cell), r.timing.median_ms / r.cell.sensors, r.error.max_abs);
        const bool first_of_workload = i == 0 || !results[i - 1].cell.same_workload(r.cell);
        if (!first_of_workload) continue;
        if (r.peer && r.peer->failure.empty())
            add(r.cell, Marker::Peer, r.peer->per_sensor.median_ms, r.peer->error.max_abs);
        if (r.cpp_peer && r.cpp_peer->failure.empty())
            add(r.cell, Marker::CppPeer, r.cpp_peer->per_sensor.median_ms, r.cpp_peer->error.max_abs);
    }
    return {pts, rows};
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
        case Marker::CppPeer:  // a triangle pointing down
            return "<polygon points=\"" + num(x) + "," + num(y + 6) + " " + num(x - 5.5) + "," + num(y - 4) + " " +
                   num(x + 5.5) + "," + num(y - 4) + "\"" + style;
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

// Each kind of point: its name in the legend and over its column of the table.
struct Kind {
    Marker marker;
    const char* legend;
    const char* column;
};
const Kind kKinds[] = {{Marker::Vulkan, "vulkan fp32", "vulkan fp32"},
                       {Marker::VulkanFp16, "vulkan fp16 storage", "vulkan fp16"},
                       {Marker::Cpu, "cpu reference (double)", "cpu (double)"},
                       {Marker::Peer, "python peer (float32)", "python"},
                       {Marker::CppPeer, "opencv c++ peer", "opencv c++"}};

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
    for (const Kind& k : kKinds) {
        s += marker_svg(k.marker, x + 6, y - 3, "#fff");
        s += text_svg(x + 18, y + 2, k.legend);
        y += 18;
    }
    s += text_svg(x, y + 12, "error 0 (the reference itself)", " font-size=\"10\"");
    s += text_svg(x, y + 25, "is drawn at 1e-10", " font-size=\"10\"");
    s += text_svg(x, y + 45, "numbers: rows of the table", " font-size=\"10\"");
    s += text_svg(x, y + 58, "below the plot", " font-size=\"10\"");
    return s;
}

struct Box {
    double x0, y0, x1, y1;
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Width and height of a label in the plot's 9 px sans-serif, a little generous.
constexpr double kLabelCharWidth = 5.6, kLabelHeight = 9;

// Each point's workload number beside it, in the first of eight places around
// the marker (then eight more, further out) that overlaps no marker, no label
// already placed and nothing outside the plotting area. A point with no free
// place stays unlabelled; the table still lists it, and the plot says how
// many there are.
std::string labels_svg(const Frame& f, const std::vector<Point>& pts, std::size_t* unlabelled) {
    std::vector<Box> taken;
    for (const auto& p : pts) taken.push_back({f.x(p.ms) - 6, f.y(p.error) - 6, f.x(p.ms) + 6, f.y(p.error) + 6});
    const Box area{f.left, f.top, f.left + f.width, f.top + f.height};
    std::string s;
    *unlabelled = 0;
    for (const auto& p : pts) {
        const std::string text = std::to_string(p.workload + 1);
        const double w = kLabelCharWidth * double(text.size()), h = kLabelHeight;
        const double mx = f.x(p.ms), my = f.y(p.error);
        bool placed = false;
        for (double d : {7.0, 15.0}) {
            // Top-left corners: right, left, above, below, then the diagonals.
            const std::pair<double, double> corners[] = {
                {mx + d, my - h / 2}, {mx - d - w, my - h / 2}, {mx - w / 2, my - d - h}, {mx - w / 2, my + d},
                {mx + d - 2, my - d - h + 2}, {mx + d - 2, my + d - 2}, {mx - d - w + 2, my - d - h + 2},
                {mx - d - w + 2, my + d - 2}};
            for (const auto& [cx, cy] : corners) {
                // 3 px of air each side, so that "3" beside "18" never reads as "318".
                const Box b{cx - 3, cy, cx + w + 3, cy + h};
                if (b.x0 < area.x0 || b.y0 < area.y0 || b.x1 > area.x1 || b.y1 > area.y1) continue;
                if (std::any_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(b); })) continue;
                taken.push_back(b);
                s += text_svg(cx, cy + h - 1.5, text, " class=\"point-label\" font-size=\"9\" fill=\"#444\"");
                placed = true;
                break;
            }
            if (placed) break;
        }
        if (!placed) ++*unlabelled;
    }
    return s;
}

std::string cell_text(const Workload& w, Marker m) {
    const auto it = w.cells.find(m);
    if (it == w.cells.end()) return "-";
    char text[48];
    std::snprintf(text, sizeof text, "%.3g ms  %.1e", it->second.first, it->second.second);
    return text;
}

constexpr double kRowHeight = 15;

// The detail the points' numbers stand for: per workload, each kind's time
// per sensor-cycle and error.
std::string table_svg(double top, const std::vector<Workload>& rows) {
    // 11 px type: a time and an error take about 95 px, a column 140.
    const double columns[] = {20, 45, 180, 245, 270, 300, 440, 580, 720, 860};
    const char* heads[] = {"#", "method", "size", "K", "S"};
    static_assert(std::size(columns) == std::size(heads) + std::size(kKinds));
    std::string s = "<g font-size=\"11\">\n";
    for (std::size_t c = 0; c < std::size(heads); ++c) s += text_svg(columns[c], top, heads[c], " font-weight=\"bold\"");
    for (std::size_t k = 0; k < std::size(kKinds); ++k)
        s += text_svg(columns[std::size(heads) + k], top, kKinds[k].column, " font-weight=\"bold\"");
    double y = top;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Workload& w = rows[i];
        y += kRowHeight;
        s += text_svg(columns[0], y, std::to_string(i + 1));
        s += text_svg(columns[1], y, w.method, (" fill=\"" + colour(w.method.substr(0, w.method.find(' '))) + "\"").c_str());
        s += text_svg(columns[2], y, w.size);
        s += text_svg(columns[3], y, std::to_string(w.frames));
        s += text_svg(columns[4], y, std::to_string(w.sensors));
        for (std::size_t k = 0; k < std::size(kKinds); ++k) s += text_svg(columns[std::size(heads) + k], y, cell_text(w, kKinds[k].marker));
    }
    return s + "</g>\n";
}

}  // namespace

void write_plot(const std::string& path, const std::vector<CellResult>& results, const std::string& device) {
    const auto [pts, rows] = collect(results);
    constexpr double kTableTop = 620;
    const double height = pts.empty() ? 600 : kTableTop + kRowHeight * double(rows.size() + 1) + 20;
    std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1000\" height=\"" + num(height) +
                      "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
    svg += text_svg(80, 28, "vkfuse-bench: time against error (" + device + ")", " font-size=\"15\"");
    if (pts.empty()) {
        svg += text_svg(80, 80, "no measured cell");
    } else {
        const Frame f = fit(pts);
        svg += axes_svg(f) + legend_svg(f, pts);
        for (const auto& p : pts) svg += marker_svg(p.marker, f.x(p.ms), f.y(p.error), colour(p.method).c_str());
        std::size_t unlabelled = 0;
        svg += labels_svg(f, pts, &unlabelled);
        if (unlabelled > 0)
            svg += text_svg(f.left + f.width, f.top - 8,
                            std::to_string(unlabelled) + " point(s) too crowded to number: see the table",
                            " text-anchor=\"end\" font-size=\"10\"");
        svg += table_svg(kTableTop, rows);
    }
    svg += "</svg>\n";
    io::write_atomically(path, [&](std::FILE* out) { io::write_all(out, svg, path); });
}

}  // namespace vkfuse::bench

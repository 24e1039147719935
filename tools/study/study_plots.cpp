#include "study/study_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vkfuse::cli {
namespace {

constexpr const char* kMetricColours[] = {"#1f77b4", "#d62728", "#2ca02c"};  // kAllMetrics order

std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", v);
    return text;
}

std::string fixed(double v, int digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

std::string open_svg(double width, double height) {
    return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) + "\" height=\"" + num(height) +
           "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
}

std::string text(double x, double y, const std::string& body, const char* anchor = "start") {
    return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" text-anchor=\"" + anchor + "\">" + body + "</text>\n";
}

std::string line(double x1, double y1, double x2, double y2, const char* colour, const char* extra = "") {
    return "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" + num(y2) +
           "\" stroke=\"" + colour + "\" " + extra + "/>\n";
}

// White at a gain of 1, saturating blue at 1/2 and red at 2 (log scale).
std::string gain_colour(double gain) {
    const double t = std::clamp(std::log2(std::max(gain, 1e-9)), -1.0, 1.0);
    const int fade = int(std::lround(255 * (1 - std::abs(t))));
    char hex[8];
    if (t >= 0)
        std::snprintf(hex, sizeof hex, "#ff%02x%02x", fade, fade);
    else
        std::snprintf(hex, sizeof hex, "#%02x%02xff", fade, fade);
    return hex;
}

}  // namespace

std::string methods_svg(const StudyResult& r) {
    const double left = 140, bar = 22, width = 560, plot = width - left - 60;
    std::string svg = open_svg(width, 40 + bar * double(r.methods.size()));
    svg += text(left, 18, "share of fusions improving every metric");
    for (std::size_t i = 0; i < r.methods.size(); ++i) {
        const double y = 28 + bar * double(i), w = plot * r.methods[i].improves_all_fraction;
        svg += text(left - 6, y + 15, r.methods[i].name, "end");
        svg += "<rect x=\"" + num(left) + "\" y=\"" + num(y + 3) + "\" width=\"" + num(w) + "\" height=\"" +
               num(bar - 6) + "\" fill=\"" + (r.methods[i].name == r.best_method ? "#d62728" : "#7f7f7f") + "\"/>\n";
        svg += text(left + w + 4, y + 15, fixed(100 * r.methods[i].improves_all_fraction, 1) + " %");
    }
    return svg + "</svg>\n";
}

std::string greedy_svg(const StudyResult& r) {
    const double left = 60, top = 30, width = 560, height = 320, plot_w = width - left - 130, plot_h = height - top - 40;
    double lo = 1, hi = 1;
    std::size_t longest = 1;
    for (const auto& steps : r.greedy)
        for (const auto& s : steps) {
            lo = std::min(lo, s.value);
            hi = std::max(hi, s.value);
            longest = std::max(longest, s.n);
        }
    if (hi - lo < 1e-9) hi = lo + 1;
    const auto x_of = [&](double n) { return left + plot_w * (longest > 1 ? (n - 1) / double(longest - 1) : 0.5); };
    const auto y_of = [&](double v) { return top + plot_h * (1 - (v - lo) / (hi - lo)); };
    std::string svg = open_svg(width, height);
    svg += text(left, 18, "greedy sequence: mean gain against the settings fused (n)");
    svg += line(left, top + plot_h, left + plot_w, top + plot_h, "black");
    svg += line(left, top, left, top + plot_h, "black");
    svg += line(left, y_of(1), left + plot_w, y_of(1), "#999999", "stroke-dasharray=\"4 3\"");
    svg += text(left - 6, y_of(1) + 4, "1", "end");
    svg += text(left - 6, y_of(hi) + 4, fixed(hi, 2), "end");
    svg += text(left - 6, y_of(lo) + 4, fixed(lo, 2), "end");
    for (std::size_t n = 1; n <= longest; ++n) svg += text(x_of(double(n)), top + plot_h + 16, std::to_string(n), "middle");
    for (std::size_t i = 0; i < 3; ++i) {
        std::string points;
        for (const auto& s : r.greedy[i]) points += num(x_of(double(s.n))) + "," + num(y_of(s.value)) + " ";
        svg += "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" + std::string(kMetricColours[i]) +
               "\" points=\"" + points + "\"/>\n";
        svg += line(left + plot_w + 12, top + 10 + 18 * double(i), left + plot_w + 32, top + 10 + 18 * double(i),
                    kMetricColours[i], "stroke-width=\"2\"");
        svg += text(left + plot_w + 36, top + 14 + 18 * double(i), std::string(to_string(kAllMetrics[i])));
    }
    return svg + "</svg>\n";
}

std::string pairing_svg(const StudyResult& r) {
    const double left = 150, cell_w = 110, cell_h = 20, top = 44;
    std::string svg = open_svg(left + 3 * cell_w + 20, top + cell_h * double(r.pairing.size()) + 10);
    svg += text(10, 18, "(" + r.settings[r.static_setting].to_string() + ") fused with each setting: gain");
    for (std::size_t i = 0; i < 3; ++i)
        svg += text(left + cell_w * (double(i) + 0.5), top - 6, std::string(to_string(kAllMetrics[i])), "middle");
    for (std::size_t row = 0; row < r.pairing.size(); ++row) {
        const auto& p = r.pairing[row];
        const double y = top + cell_h * double(row);
        svg += text(left - 6, y + 14, "(" + r.settings[p.settings[0]].to_string() + ")", "end");
        for (std::size_t i = 0; i < 3; ++i) {
            const double g = p.gain.of(kAllMetrics[i]);
            svg += "<rect x=\"" + num(left + cell_w * double(i)) + "\" y=\"" + num(y) + "\" width=\"" + num(cell_w) +
                   "\" height=\"" + num(cell_h) + "\" fill=\"" + gain_colour(g) + "\" stroke=\"white\"/>\n";
            svg += text(left + cell_w * (double(i) + 0.5), y + 14, fixed(g, 3), "middle");
        }
    }
    return svg + "</svg>\n";
}

}  // namespace vkfuse::cli

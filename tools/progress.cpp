#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace vkfuse::cli {

Progress::Progress(std::string prefix) : prefix_(std::move(prefix)), tty_(::isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() { finish(); }

bool Progress::due(double interval_s) {
    const auto now = Clock::now();
    if (last_draw_ != Clock::time_point{} && std::chrono::duration<double>(now - last_draw_).count() < interval_s)
        return false;
    last_draw_ = now;
    return true;
}

void Progress::draw(const std::string& text) {
    if (tty_) {
        std::fprintf(stderr, "\r\033[K%s: %s", prefix_.c_str(), text.c_str());  // \033[K clears the rest of the line
        open_line_ = true;
    } else {
        std::fprintf(stderr, "%s: %s\n", prefix_.c_str(), text.c_str());
    }
    std::fflush(stderr);
}

void Progress::fraction(std::size_t done, std::size_t total, const std::string& unit) {
    const double f = total ? double(done) / double(total) : 1.0;
    const std::string counts = std::to_string(done) + "/" + std::to_string(total) + " " + unit;
    if (!tty_) {
        const int decile = int(f * 10.0);
        if (decile == last_decile_) return;
        last_decile_ = decile;
        draw(std::to_string(decile * 10) + "% (" + counts + ")");
        return;
    }
    if (done != total && !due(0.1)) return;
    constexpr int kWidth = 30;
    const int filled = int(f * kWidth);
    char percent[16];
    std::snprintf(percent, sizeof percent, "%3d%%", int(f * 100.0));
    draw("[" + std::string(std::size_t(filled), '#') + std::string(std::size_t(kWidth - filled), '.') + "] " + percent +
         " " + counts);
}

void Progress::status(const std::string& text) {
    if (due(tty_ ? 0.2 : 10.0)) draw(text);
}

void Progress::finish() {
    if (!open_line_) return;
    std::fputc('\n', stderr);
    std::fflush(stderr);
    open_line_ = false;
}

}  // namespace vkfuse::cli

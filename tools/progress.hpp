// progress.hpp - progress on stderr: redrawn in place on a terminal, an
// occasional plain line otherwise (a log or a pipe gets no carriage returns).
#pragma once
#include <chrono>
#include <cstddef>
#include <string>

namespace vkfuse::cli {

class Progress {
public:
    explicit Progress(std::string prefix);  // "vkfuse sim"
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // A bar on a terminal; otherwise a percentage line at every 10 %.
    void fraction(std::size_t done, std::size_t total, const std::string& unit);
    // A live status line: on a terminal redrawn at most 5 times a second;
    // otherwise printed every 10 seconds.
    void status(const std::string& text);
    // Ends a line drawn in place, so what follows starts on a fresh line.
    void finish();

private:
    using Clock = std::chrono::steady_clock;
    std::string prefix_;
    bool tty_;
    bool open_line_ = false;
    int last_decile_ = -1;
    Clock::time_point last_draw_{};

    bool due(double interval_s);
    void draw(const std::string& text);
};

}  // namespace vkfuse::cli

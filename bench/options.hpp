// vkfuse-bench's command line: which part of the matrix to run and what to write.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "axes.hpp"

namespace vkfuse::bench {

// vkfuse-bench's command line: which part of the matrix to run and what to write.

enum class Scope {
    Default,  // a subset that finishes in a few minutes on lavapipe
    Quick,    // seconds: the smoke run CI and ctest use
    Full,     // every cell of the matrix
};

struct Options {
    Scope scope = Scope::Default;
    // Axis filters; an empty list leaves the scope's list for that axis.
    std::vector<Method> methods;
    std::vector<Wavelet> wavelets;
    std::vector<Backend> backends;
    std::vector<Size> sizes;
    std::vector<int> frames;
    std::vector<int> sensors;
    std::vector<int> levels;
    std::vector<Precision> precisions;
    std::string json_path;
    std::string plot_path;
    bool profile = false;
    bool peers = true;
    std::string python;          // the peers' interpreter; empty: /usr/bin/python3, then python3
    int runs = 20;               // timed cycles per cell
    int warmup = 2;              // untimed cycles before them
    double cell_seconds = 60;    // run budget of one cell where runs may be capped
    int device = -1;             // Vulkan device index, -1: the best one
    double mem_limit_gib = 0;    // 0: 80% of the memory available at start
    bool list = false;           // print the cells and exit
    bool probe = false;          // measure the device, print it, run no cell
    bool windows = false;        // sliding windows against cycles on simulated scenes (windows.hpp)
    bool scenes = false;         // skipping on simulated scenes instead of the matrix (scenes.hpp)
    bool pipeline = false;       // round trip against two cycles in flight instead of the matrix (pipeline.hpp)
    bool help = false;
};

// Throws UsageError with a one-line message on any bad option or value.
Options parse_options(const std::vector<std::string>& args);

std::string help_text();

// A bad command line: main() prints the message on one line and exits 2.

class UsageError : public std::runtime_error {
public:
    explicit UsageError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vkfuse::bench

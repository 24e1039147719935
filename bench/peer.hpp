// The peers run on the same frames as vkfuse, so speed and error are compared
// within one run: the Python pipelines (bench/peers/pipelines.py) and the C++
// ones written with OpenCV's API (bench/peers/opencv_peer.cpp: Laplacian,
// Brovey, channel-sum).
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "inputs.hpp"
#include "result.hpp"

namespace vkfuse::bench {

class PeerRunner {
public:
    // Finds an interpreter that imports numpy, pywt and cv2: `python` when
    // given, else /usr/bin/python3 (Debian's, with python3-pywt and
    // python3-opencv), then python3 on PATH. Without one (or without the
    // script) available() is false.
    PeerRunner(std::string script, const std::string& python);
    // The C++ peer at `program` (empty: not built), which runs `methods` only.
    static PeerRunner program(const std::string& program, std::vector<Method> methods);

    bool available() const { return !prefix_.empty(); }
    // Whether it runs the cell's method.
    bool runs(const Cell& cell) const {
        return only_.empty() || std::find(only_.begin(), only_.end(), cell.method.method) != only_.end();
    }
    // "laplacian, brovey" (empty: every method).
    std::string methods() const;
    const std::string& python() const { return python_; }
    const std::string& why_not() const { return why_not_; }

    // Runs the cell's method on sensor 0's frames (expected: sensor 0's
    // reference). A failing peer gives a result with `failure` set.
    PeerResult run(const Cell& cell, const Inputs& in, const Expected& sensor0, double max_seconds, int runs) const;

private:
    PeerRunner() = default;
    std::string script_;
    std::string python_;
    std::vector<std::string> prefix_;  // the command before the arguments: interpreter and script, or the program
    std::vector<Method> only_;  // empty: every method
    std::string why_not_;
};

}  // namespace vkfuse::bench

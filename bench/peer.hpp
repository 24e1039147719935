// The Python peers (bench/peers/pipelines.py) run on the same frames as
// vkfuse, so speed and error are compared within one run.
#pragma once
#include <string>

#include "cell.hpp"
#include "expected.hpp"
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

    bool available() const { return !python_.empty(); }
    const std::string& python() const { return python_; }
    const std::string& why_not() const { return why_not_; }

    // Runs the cell's method on sensor 0's frames (expected: sensor 0's
    // reference). A failing peer gives a result with `failure` set.
    PeerResult run(const Cell& cell, const Inputs& in, const Expected& sensor0, double max_seconds, int runs) const;

private:
    std::string script_;
    std::string python_;
    std::string why_not_;
};

}  // namespace vkfuse::bench

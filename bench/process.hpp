// Running a helper program (the Python peers) and capturing what it prints.
#pragma once
#include <string>
#include <vector>

namespace vkfuse::bench {

struct ProcessResult {
    bool started = false;  // false: the program could not be run at all
    int exit_code = -1;    // -1 when killed by a signal
    std::string out;       // all of stdout
    std::string err;       // all of stderr
};

// Runs argv[0] (searched on PATH when it has no '/') with argv, stdin from
// /dev/null, and waits for it.
ProcessResult run_process(const std::vector<std::string>& argv);

// The last non-empty line of text (for one-line error messages).
std::string last_line(const std::string& text);

}  // namespace vkfuse::bench

// Running a helper program (the Python peers) in a private temporary
// directory and capturing what it prints.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace vkfuse::bench {

// Running a helper program (the Python peers) and capturing what it prints.

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

// A private temporary directory, removed with everything in it when done.

class TempDir {
public:
    TempDir();  // under $TMPDIR (or /tmp); throws std::runtime_error on failure
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace vkfuse::bench

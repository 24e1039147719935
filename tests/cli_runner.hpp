// cli_runner.hpp - runs the built `vkfuse` binary (VKFUSE_CLI) and captures
// its exit status, stdout and stderr. Header-only for the test_cli_* files.
#pragma once
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "temp_dir.hpp"

extern char** environ;

namespace vkfuse::test {

// text's lines, without their newlines (a last line may lack one).
inline std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    for (std::size_t start = 0, end; start < text.size(); start = end + 1) {
        end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        lines.push_back(text.substr(start, end - start));
    }
    return lines;
}

struct CliResult {
    int status = -1;  // exit status, or 128 + signal
    std::string out;
    std::string err;

    std::vector<std::string> err_lines() const { return lines_of(err); }
};

// The current environment with extra "NAME=value" entries replacing any of the same name.
inline std::vector<std::string> environment_with(const std::vector<std::string>& extra) {
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e) {
        std::string entry(*e);
        bool replaced = false;
        for (const std::string& x : extra) replaced = replaced || entry.rfind(x.substr(0, x.find('=') + 1), 0) == 0;
        if (!replaced) env.push_back(entry);
    }
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
}

inline std::vector<char*> c_strings(std::vector<std::string>& words) {
    std::vector<char*> out;
    for (std::string& w : words) out.push_back(w.data());
    out.push_back(nullptr);
    return out;
}

// Far above any command the tests run (the slowest takes seconds on lavapipe).
inline constexpr std::chrono::seconds kCliTimeout{300};

// Starts vkfuse with args in the background, stdout and stderr to the files
// named ("/dev/null" to drop), extra_env as in environment_with; returns its
// pid for kill/waitpid.
inline pid_t start_cli(const std::vector<std::string>& args, const std::string& out_path,
                       const std::string& err_path, const std::vector<std::string>& extra_env = {}) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> words{VKFUSE_CLI};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<std::string> env = environment_with(extra_env);
    std::vector<char*> argv = c_strings(words), envp = c_strings(env);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, VKFUSE_CLI, &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start " + std::string(VKFUSE_CLI));
    return pid;
}

// The staging directory a running `vkfuse run` / `vkfuse sim` writes into
// (".vkfuse-partial-*" beside its output) that holds entry ("" for any), or
// "" while there is none. (`run --out --record` stages two.)
inline std::string staging_directory(const std::string& parent, const std::string& entry = "") {
    for (const auto& e : std::filesystem::directory_iterator(parent))
        if (e.path().filename().string().rfind(".vkfuse-partial-", 0) == 0 &&
            (entry.empty() || std::filesystem::exists(e.path() / entry)))
            return e.path().string();
    return {};
}

inline CliResult run_cli(const std::vector<std::string>& args, const std::vector<std::string>& extra_env = {}) {
    TempDir capture;
    const std::string out_path = capture.file("stdout"), err_path = capture.file("stderr");
    const pid_t pid = start_cli(args, out_path, err_path, extra_env);
    // A command that hangs (it once waited forever on a FIFO given as input)
    // is killed, so the test fails with a message instead of never ending.
    int wstatus = 0;
    const auto deadline = std::chrono::steady_clock::now() + kCliTimeout;
    bool killed = false;
    for (;;) {
        pid_t done = waitpid(pid, &wstatus, WNOHANG);
        if (done == pid) break;
        if (done < 0) throw std::runtime_error("waitpid failed");
        if (!killed && std::chrono::steady_clock::now() > deadline) {
            ::kill(pid, SIGKILL);
            killed = true;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    CliResult result;
    result.status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
    result.out = read_bytes(out_path);
    result.err = read_bytes(err_path);
    if (killed) result.err += "(cli_runner: killed after " + std::to_string(kCliTimeout.count()) + " s)\n";
    return result;
}

// `vkfuse run --virtual-clock --cycles 1` plus extra is refused before any
// work: status 2, the one line "vkfuse: <message>", nothing on stdout.
inline void expect_run_refused(const std::vector<std::string>& extra, const std::string& message) {
    std::vector<std::string> args{"run", "--virtual-clock", "--cycles", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 2) << message;
    EXPECT_EQ(r.err, "vkfuse: " + message + "\n");
    EXPECT_TRUE(r.out.empty());
}

}  // namespace vkfuse::test

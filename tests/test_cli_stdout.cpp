// What a command prints on stdout is one of its results: on a full device
// (/dev/full) every command fails with one line, and one that publishes files
// (run, sim, study, tune) publishes nothing.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <filesystem>

#include "cli_runner.hpp"
#include "study_dataset.hpp"

namespace vkfuse::test {
namespace {

CliResult run_onto_full_device(const std::vector<std::string>& args) {
    TempDir capture;
    const pid_t pid = start_cli(args, "/dev/full", capture.file("stderr"));
    int status = 0;
    EXPECT_EQ(waitpid(pid, &status, 0), pid);
    CliResult r;
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.err = read_bytes(capture.file("stderr"));
    return r;
}

TEST(CliStdout, EveryCommandFailsOnAFullDevice) {
    TempDir tmp;
    write_study_dataset(tmp.file("dataset"));
    const std::vector<std::vector<std::string>> commands{
        {"--help"},
        {"--version"},
        {"info"},
        {"devices", "--help"},
        {"run", "--help"},
        {"sim", "--out", tmp.file("set"), "--objects", "coin", "--grid", "0,15", "--frames", "1"},
        {"run", "--virtual-clock", "--cycles", "1", "--backend", "cpu", "--method", "brovey", "--out", tmp.file("o")},
        {"metrics", VKFUSE_TEST_DATA "/demo_white.png"},
        {"study", tmp.file("dataset"), "--max-k", "2", "--backend", "cpu", "--out", tmp.file("study")},
        {"tune", "--dataset", tmp.file("dataset"), "--max-k", "2", "--backend", "cpu", "--out", tmp.file("c.json")},
    };
    for (const auto& args : commands) {
        std::string line;
        for (const std::string& a : args) line += a + " ";
        SCOPED_TRACE(line);
        const CliResult r = run_onto_full_device(args);
        EXPECT_EQ(r.status, 2);
        const std::string expected = "vkfuse: stdout: write failed: No space left on device\n";
        EXPECT_TRUE(r.err.size() >= expected.size() && r.err.substr(r.err.size() - expected.size()) == expected)
            << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(tmp.file("set")));
    EXPECT_FALSE(std::filesystem::exists(tmp.file("o")));
    EXPECT_FALSE(std::filesystem::exists(tmp.file("study")));
    EXPECT_FALSE(std::filesystem::exists(tmp.file("c.json")));
    EXPECT_EQ(staging_directory(tmp.file("")), "");
}

}  // namespace
}  // namespace vkfuse::test

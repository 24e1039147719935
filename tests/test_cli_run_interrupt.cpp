// vkfuse run stopped before its first cycle: a run that fused nothing
// publishes nothing and replaces nothing (one stopped after some cycles:
// CliRunUnlucky.SigtermFinishesTheRunAndTheRecording).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "cli_runner.hpp"

namespace vkfuse::test {
namespace {

namespace fs = std::filesystem;

bool has(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

std::size_t count_lines(const std::string& text) { return std::size_t(std::count(text.begin(), text.end(), '\n')); }

// Waits for `vkfuse run` (pid) to have made its staging directory in parent,
// which it does after its options are checked and before its sensors start.
void wait_for_staging(const std::string& parent) {
    for (int i = 0; i < 3000 && staging_directory(parent).empty(); ++i) usleep(10000);
    ASSERT_FALSE(staging_directory(parent).empty()) << "no staging directory appeared in " << parent;
}

int exit_status(pid_t pid) {
    int status = 0;
    EXPECT_EQ(waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// The quick start's own run passes --replace. Interrupted while its two
// sensors still take their backgrounds (20 frames under each setting, seconds
// of rendering), a run has fused nothing: it fails, the previous run's
// directory keeps its files and no recording appears, for Ctrl-C and SIGTERM.
TEST(CliRunInterrupt, AnInterruptBeforeTheFirstCycleReplacesNothing) {
    TempDir tmp;
    const CliResult first = run_cli({"run", "--virtual-clock", "--cycles", "5", "--backend", "cpu", "--method",
                                     "brovey", "--out", tmp.file("rp")});
    ASSERT_EQ(first.status, 0) << first.err;
    const std::string before = read_bytes(tmp.file("rp/metrics.jsonl"));
    ASSERT_EQ(count_lines(before), 5u);
    for (int sig : {SIGINT, SIGTERM}) {
        SCOPED_TRACE(sig == SIGINT ? "SIGINT" : "SIGTERM");
        const pid_t pid = start_cli({"run", "--virtual-clock", "--sensors", "2", "--cycles", "100", "--backend",
                                     "cpu", "--method", "brovey", "--out", tmp.file("rp"), "--replace", "--record",
                                     tmp.file("rec")},
                                    tmp.file("stdout"), tmp.file("stderr"));
        wait_for_staging(tmp.file(""));
        ::kill(pid, sig);
        EXPECT_EQ(exit_status(pid), 2);
        const std::string err = read_bytes(tmp.file("stderr"));
        EXPECT_TRUE(has(err, "vkfuse: interrupted before any cycle was fused; nothing written; --out " +
                                 tmp.file("rp") + " and --record " + tmp.file("rec") + " left as they were\n"))
            << err;
        EXPECT_EQ(read_bytes(tmp.file("stdout")), "");
        EXPECT_EQ(read_bytes(tmp.file("rp/metrics.jsonl")), before);
        EXPECT_FALSE(fs::exists(tmp.file("rec")));
        EXPECT_EQ(staging_directory(tmp.file("")), "");
    }
}

}  // namespace
}  // namespace vkfuse::test

// Bad input to vkfuse run and vkfuse sim: exit 2, one line naming the
// problem, nothing on stdout, no directory created.
#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace vkfuse::test {
namespace {

struct BadRun {
    std::string name;
    std::vector<std::string> args;  // "@x" stands for x in the test's directory
    std::string fragment;
};

std::vector<BadRun> bad_runs() {
    const std::vector<std::string> run{"run", "--virtual-clock", "--cycles", "1", "--out", "@out", "--record", "@rec"};
    auto with = [](std::vector<std::string> base, std::vector<std::string> more) {
        base.insert(base.end(), more.begin(), more.end());
        return base;
    };
    return {
        {"unknown_object", with(run, {"--object", "spoon"}), "--object spoon: unknown object (expected nothing, "},
        {"sequence_not_numbers", with(run, {"--sequence", "15,15,15+bright"}), "--sequence 15,15,15+bright: "},
        {"sequence_two_leds", with(run, {"--sequence", "15,15+0,15,0"}), "--sequence 15,15+0,15,0: "},
        {"sequence_level_out_of_range", with(run, {"--sequence", "15,15,15+0,16,0"}), "level 16 of g exceeds 15"},
        {"sequence_empty_setting", with(run, {"--sequence", "15,15,15++0,15,0"}), "--sequence 15,15,15++0,15,0: "},
        {"zero_sensors", with(run, {"--sensors", "0"}), "--sensors 0: expected a positive integer"},
        {"too_many_sensors", with(run, {"--sensors", "65"}), "--sensors 65: at most 64"},
        {"zero_cycles", {"run", "--cycles", "0"}, "--cycles 0: expected a positive integer"},
        {"bad_duration", {"run", "--duration", "-2"}, "--duration -2: expected a positive number of seconds"},
        {"bad_timeout", {"run", "--timeout", "soon"}, "--timeout soon: expected a positive number of seconds"},
        {"bad_background_frames",
         {"run", "--background-frames", "x"},
         "--background-frames x: expected a non-negative"},
        {"impossible_levels", with(run, {"--levels", "9"}), "--levels 9: a 240x320 image carries at most"},
        {"unknown_method", with(run, {"--method", "median"}), "--method: unknown method \"median\""},
        {"channel_sum_needs_three", with(run, {"--method", "channel-sum"}), "needs exactly 3 frames"},
        {"replay_missing", {"run", "--replay", "@absent", "--out", "@out"}, "@absent/manifest.json: cannot open"},
        {"replay_with_sensors",
         {"run", "--replay", "@absent", "--sensors", "2"},
         "--sensors does not apply to --replay"},
        {"unknown_motion", with(run, {"--motion", "wiggle"}), "--motion: unknown motion \"wiggle\" (expected still, tap"},
        {"motion_too_fast", with(run, {"--motion", "tap", "--motion-period", "0.01"}),
         "--motion-period 0.01: shorter than the simulator's shortest motion period (0.05 s)"},
        {"bad_motion_period", with(run, {"--motion-period", "x"}), "--motion-period x: expected a positive number"},
        {"replay_with_motion",
         {"run", "--replay", "@absent", "--motion", "tap"},
         "--motion does not apply to --replay"},
        {"flag_with_value", {"run", "--virtual-clock=yes"}, "option --virtual-clock takes no value"},
        {"operand", {"run", "coin"}, "run: unexpected operand coin"},
        {"unknown_backend", with(run, {"--backend", "gpu"}), "--backend gpu: expected cpu, vulkan or auto"},
        {"sim_unknown_object",
         {"sim", "--out", "@set", "--objects", "coin,spoon"},
         "--objects spoon: unknown object (expected nothing, "},
        {"sim_grid_level", {"sim", "--out", "@set", "--grid", "0,16"}, "--grid 0,16: level 16 exceeds 15"},
        {"sim_grid_junk", {"sim", "--out", "@set", "--grid", "0,x"}, "--grid x: expected a non-negative integer"},
        {"sim_zero_frames", {"sim", "--out", "@set", "--frames", "0"}, "--frames 0: expected a positive integer"},
        {"sim_operand", {"sim", "extra"}, "sim: unexpected operand extra"},
    };
}

std::string expand(const TempDir& dir, const std::string& word) {
    return word.size() > 1 && word[0] == '@' ? dir.file(word.substr(1)) : word;
}

class CliRunErrors : public ::testing::TestWithParam<BadRun> {};

TEST_P(CliRunErrors, ExitTwoWithOneLineAndNothingWritten) {
    const BadRun& bad = GetParam();
    TempDir dir;
    std::vector<std::string> args;
    for (const std::string& a : bad.args) args.push_back(expand(dir, a));
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.out, "");
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("vkfuse: ", 0), 0u) << r.err;
    std::string fragment = bad.fragment;
    if (const std::size_t at = fragment.find('@'); at != std::string::npos) {
        const std::size_t end = fragment.find('/', at);
        fragment.replace(at, end - at, dir.file(fragment.substr(at + 1, end - at - 1)));
    }
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{});
}

INSTANTIATE_TEST_SUITE_P(BadInput, CliRunErrors, ::testing::ValuesIn(bad_runs()),
                         [](const auto& info) { return info.param.name; });

// A recording needs a new directory; the run refuses before it starts.
TEST(CliRunErrors, RecordingIntoAUsedDirectory) {
    TempDir dir;
    write_bytes(dir.file("keep.txt"), "mine");
    const CliResult r = run_cli({"run", "--virtual-clock", "--cycles", "1", "--record", dir.file("")});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("exists and is not empty"), std::string::npos) << r.err;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"keep.txt"});
}

TEST(CliRunHelp, ListsOptionsAndObjects) {
    for (const char* command : {"run", "sim"}) {
        const CliResult r = run_cli({command, "--help"});
        EXPECT_EQ(r.status, 0);
        EXPECT_NE(r.out.find("Usage: vkfuse " + std::string(command)), std::string::npos) << r.out;
    }
    const CliResult run = run_cli({"run", "--help"});
    for (const char* m : {"--sensors N", "--sequence SEQ", "--virtual-clock ", "--replay DIR", "--record DIR",
                          "--out DIR", "--cycles N", "--duration SECONDS", "--wavelet W", "coin-tails"})
        EXPECT_NE(run.out.find(m), std::string::npos) << m;
}

}  // namespace
}  // namespace vkfuse::test

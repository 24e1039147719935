// `vkfuse run` and real DIGITs on a machine without any: the fallback to the
// simulator is said in one line, and naming a DIGIT that is not there is
// refused in one line. Streaming from one is tested against an emulated
// DIGIT (ctest -L hil).
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "vkfuse/sensor/digit.hpp"

namespace vkfuse::test {
namespace {

bool digits_plugged_in() { return !find_digits().empty(); }

TEST(CliRunDigits, WithoutADigitTheSimulatorRunsAndSaysSo) {
    if (digits_plugged_in()) GTEST_SKIP() << "a DIGIT is plugged into this machine";
    const CliResult r = run_cli({"run", "--cycles", "1", "--background-frames", "0"});
    ASSERT_EQ(r.status, 0) << r.err;
    // The choice, then the progress line every run ends with.
    const std::vector<std::string> lines = r.err_lines();
    ASSERT_EQ(lines.size(), 2u) << r.err;
    EXPECT_EQ(lines[0], "vkfuse run: no DIGIT found; simulating 1 DIGIT (SIM-0001)");
    EXPECT_EQ(lines[1].rfind("vkfuse run: cycle 1/1", 0), 0u) << lines[1];
    EXPECT_NE(r.out.find("\"fused\": 1"), std::string::npos) << r.out;
}

TEST(CliRunDigits, AskingForTheSimulatorNeedsNoWord) {
    for (const char* option : {"--simulate", "--virtual-clock"}) {
        const CliResult r = run_cli({"run", option, "--cycles", "1", "--background-frames", "0"});
        ASSERT_EQ(r.status, 0) << option << ": " << r.err;
        EXPECT_EQ(r.err.find("DIGIT"), std::string::npos) << option << ": " << r.err;
        EXPECT_EQ(r.err_lines().size(), 1u) << r.err;  // the progress line alone
    }
}

TEST(CliRunDigits, ADigitThatIsNotThereIsRefusedInOneLine) {
    const CliResult r = run_cli({"run", "--sensor", "D99999", "--cycles", "1"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err.rfind("vkfuse: --sensor D99999: no DIGIT with this serial is plugged in (", 0), 0u) << r.err;
    EXPECT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_TRUE(r.out.empty());
    const CliResult node = run_cli({"run", "--sensor", "/dev/video99", "--cycles", "1"});
    EXPECT_EQ(node.status, 2);
    EXPECT_EQ(node.err.rfind("vkfuse: --sensor /dev/video99: not the capture node of a DIGIT", 0), 0u) << node.err;
}

TEST(CliRunDigits, SimulatorOptionsDoNotApplyToRealDigits) {
    for (const char* option : {"--virtual-clock", "--simulate", "--camera-auto"}) {
        const CliResult r = run_cli({"run", "--sensor", "D20001", option, "--cycles", "1"});
        EXPECT_EQ(r.status, 2) << option;
        EXPECT_EQ(r.err, "vkfuse: run: " + std::string(option) +
                             " does not apply to real DIGITs (--sensor) (see 'vkfuse run --help')\n");
    }
    const CliResult bad = run_cli({"run", "--encoding", "h264", "--cycles", "1"});
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err, "vkfuse: --encoding: unknown encoding 'h264' (yuyv or mjpeg)\n");
}

}  // namespace
}  // namespace vkfuse::test

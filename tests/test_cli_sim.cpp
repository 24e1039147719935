// vkfuse sim: a dataset per object x illumination from the simulated DIGIT,
// with progress on stderr, that vkfuse run can replay.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::test {
namespace {

TEST(CliSim, RendersADatasetRunCanReplay) {
    TempDir tmp;
    const std::string dir = tmp.file("set");
    const CliResult r = run_cli(
        {"sim", "--out", dir, "--objects", "coin,lego", "--grid", "0,15", "--frames", "2", "--background-frames", "1"});
    ASSERT_EQ(r.status, 0) << r.err;
    // stderr is no terminal here: plain percentage lines, no carriage returns.
    EXPECT_EQ(r.err.find('\r'), std::string::npos);
    EXPECT_NE(r.err.find("vkfuse sim: 100% (40/40 frames)\n"), std::string::npos) << r.err;
    const Dataset d = read_dataset(dir);
    EXPECT_EQ(d.source, "vkfuse sim");
    ASSERT_EQ(d.sensors.size(), 1u);
    const DatasetSensorRecord& s = d.sensors[0];
    EXPECT_EQ(s.info.serial, "SIM-0001");
    ASSERT_EQ(s.takes.size(), 3u);
    EXPECT_TRUE(s.takes[0].background);
    EXPECT_EQ(s.takes[0].frames.size(), 8u);  // 2^3 settings x 1
    EXPECT_EQ(s.takes[1].object, "coin");
    EXPECT_EQ(s.takes[2].frames.size(), 16u);
    EXPECT_EQ(s.takes[2].frames[15].illumination, Illumination::parse("15,15,15"));

    const CliResult replay = run_cli({"run", "--replay", dir, "--object", "lego", "--sequence", "15,15,15+0,15,0",
                                      "--method", "brovey", "--out", tmp.file("out")});
    ASSERT_EQ(replay.status, 0) << replay.err;
    // Two frames per setting were recorded: two cycles, each with the recorded background.
    EXPECT_NE(replay.out.find("\"cycles\": 2, \"sensors\": 1, \"submits\": 2, \"fused\": 2,"), std::string::npos)
        << replay.out;
    EXPECT_NE(read_bytes(tmp.file("out/metrics.jsonl")).find("\"object\": \"lego\""), std::string::npos);
}

}  // namespace
}  // namespace vkfuse::test

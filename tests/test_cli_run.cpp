// vkfuse run end to end: the default simulated coin, sixteen sensors with one
// submit per cycle, and a recorded run replayed bit for bit.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "cli_runner.hpp"
#include "run/caption.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

namespace fs = std::filesystem;

bool has(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

TEST(CliRun, SimulatedCoinWithOutputs) {
    TempDir tmp;
    const CliResult r =
        run_cli({"run", "--virtual-clock", "--cycles", "3", "--background-frames", "2", "--out", tmp.file("out")});
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(lines_of(r.out).size(), 1u) << r.out;
    // The coin is held still: the first cycle is fused and the others reuse
    // its result (--skip tiles, the default, reuses as static does).
    EXPECT_TRUE(has(r.out, "\"cycles\": 3, \"sensors\": 1, \"submits\": 1, \"fused\": 3,")) << r.out;
    EXPECT_TRUE(has(r.out, "\"switch_timing\": {\"SIM-0001\": {\"frame_period_s\": ")) << r.out;
    // A virtual clock's switch requests are never late: the normal scheduler.
    EXPECT_TRUE(has(r.out, "\"switch_scheduling\": {\"SIM-0001\": \"normal\"}")) << r.out;
    const std::vector<std::string> metrics = lines_of(read_bytes(tmp.file("out/metrics.jsonl")));
    ASSERT_EQ(metrics.size(), 3u);
    for (const std::string& m : metrics) {
        EXPECT_TRUE(has(m, "\"sensor\": \"SIM-0001\", \"status\": \"ok\", \"object\": \"coin\"")) << m;
        EXPECT_TRUE(has(m, "\"background_diff\": ")) << m;
    }
    EXPECT_EQ(
        files_under(tmp.file("out")),
        (std::vector<std::string>{"fused/SIM-0001/000000.png", "fused/SIM-0001/000001.png", "fused/SIM-0001/000002.png",
                                  "metrics.jsonl", "side_by_side/coin_SIM-0001.png", "summary.json"}));
    // static | fused under a caption of three lines (tools/run/caption.hpp):
    // the fused side is the last cycle's fused PNG.
    const Image pair = io::read_image(tmp.file("out/side_by_side/coin_SIM-0001.png"));
    const Image fused = io::read_image(tmp.file("out/fused/SIM-0001/000002.png"));
    const int band = 3 * (cli::kGlyphHeight + 5) + 4;
    EXPECT_EQ(pair.width, 2 * 320 + 8);
    ASSERT_EQ(pair.height, 240 + band);
    for (int y = 0; y < 240; y += 7)
        for (int x = 0; x < 320; x += 5)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(pair.at(band + y, 328 + x, c), fused.at(y, x, c)) << y << " " << x;
    float light = 0;  // the caption's text
    for (int y = 0; y < band; ++y)
        for (int x = 0; x < pair.width; ++x) light += pair.at(y, x, 0) > 0.5f;
    EXPECT_GT(light, 500.0f);
    EXPECT_EQ(read_bytes(tmp.file("out/summary.json")), r.out);
}

// --motion tap: the coin is pressed for the first half of each period and
// lifted for the second, and the fused cycles show it - the difference with
// the background rises and falls with the taps.
TEST(CliRun, TapMotionComesAndGoesInTheMetrics) {
    TempDir tmp;
    const CliResult r = run_cli({"run", "--virtual-clock", "--cycles", "24", "--background-frames", "2", "--motion",
                                 "tap", "--motion-period", "0.5", "--method", "brovey", "--skip", "off",
                                 "--out", tmp.file("out")});
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<double> diffs;
    for (const std::string& m : lines_of(read_bytes(tmp.file("out/metrics.jsonl")))) {
        const std::size_t at = m.find("\"background_diff\": ");
        ASSERT_NE(at, std::string::npos) << m;
        diffs.push_back(std::stod(m.substr(at + 19)));
    }
    ASSERT_EQ(diffs.size(), 24u);
    const auto [low, high] = std::minmax_element(diffs.begin(), diffs.end());
    EXPECT_GT(*high, 4 * *low) << "pressed and lifted cycles look alike";
    // Each cycle takes about 0.07 s of sensor time (every cycle captures
    // both settings: --skip off, so no watch cycles): 24 cycles span three
    // taps, so the contact comes and goes at least twice.
    const double middle = (*low + *high) / 2;
    int changes = 0;
    for (std::size_t i = 1; i < diffs.size(); ++i) changes += (diffs[i] > middle) != (diffs[i - 1] > middle);
    EXPECT_GE(changes, 4);
}

TEST(CliRun, SixteenSensorsOneSubmitPerCycle) {
    TempDir tmp;
    const CliResult r = run_cli({"run", "--sensors", "16", "--cycles", "2", "--virtual-clock", "--background-frames",
                                 "1", "--method", "brovey", "--out", tmp.file("out")});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(has(r.out, "\"cycles\": 2, \"sensors\": 16, \"submits\": 2, \"fused\": 32,")) << r.out;
    const std::vector<std::string> metrics = lines_of(read_bytes(tmp.file("out/metrics.jsonl")));
    ASSERT_EQ(metrics.size(), 32u);
    EXPECT_TRUE(has(metrics[15], "\"cycle\": 0, \"sensor\": \"SIM-0016\", \"status\": \"ok\"")) << metrics[15];
    EXPECT_TRUE(has(metrics[16], "\"cycle\": 1, \"sensor\": \"SIM-0001\", \"status\": \"ok\"")) << metrics[16];
}

// Two runs' --out directories hold the same metrics.jsonl, the same files and
// the same fused PNGs, byte for byte.
void expect_same_outputs(const TempDir& tmp, const std::string& expected, const std::string& actual) {
    EXPECT_EQ(read_bytes(tmp.file(actual + "/metrics.jsonl")), read_bytes(tmp.file(expected + "/metrics.jsonl")));
    const std::vector<std::string> files = files_under(tmp.file(expected));
    EXPECT_EQ(files_under(tmp.file(actual)), files);
    for (const std::string& f : files) {
        if (f.rfind("fused/", 0) == 0) {
            EXPECT_EQ(read_bytes(tmp.file(actual + "/" + f)), read_bytes(tmp.file(expected + "/" + f))) << f;
        }
    }
}

// Two cycles in flight: the device fuses cycle c + 1 while c is written; the
// run writes exactly what a round trip per cycle writes.
TEST(CliRun, TwoCyclesInFlightWriteWhatTheRoundTripWrites) {
    TempDir tmp;
    const CliResult recorded =
        run_cli({"run", "--virtual-clock", "--sensors", "2", "--cycles", "4", "--background-frames", "2", "--skip",
                 "off", "--method", "wavelet", "--record", tmp.file("rec")});
    ASSERT_EQ(recorded.status, 0) << recorded.err;
    for (const char* n : {"1", "2"}) {
        const CliResult r = run_cli({"run", "--replay", tmp.file("rec"), "--skip", "off", "--cycles-in-flight", n,
                                     "--out", tmp.file(std::string("out") + n)});
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_TRUE(has(r.out, "\"cycles\": 4, \"sensors\": 2,")) << r.out;
        EXPECT_TRUE(has(r.out, std::string("\"cycles_in_flight\": ") + n + ",")) << r.out;
    }
    expect_same_outputs(tmp, "out1", "out2");
}

TEST(CliRun, ReplayReproducesTheRecordedRun) {
    TempDir tmp;
    const std::vector<std::string> common{"--sequence", "15,15,15+0,15,0+15,0,0", "--method", "laplacian"};
    std::vector<std::string> live{"run",   "--virtual-clock",     "--sensors", "2",        "--cycles",
                                  "3",     "--background-frames", "2",         "--record", tmp.file("rec"),
                                  "--out", tmp.file("live")};
    live.insert(live.end(), common.begin(), common.end());
    const CliResult recorded = run_cli(live);
    ASSERT_EQ(recorded.status, 0) << recorded.err;
    // Sequence and method come from the recording.
    const CliResult replayed = run_cli({"run", "--replay", tmp.file("rec"), "--out", tmp.file("again")});
    ASSERT_EQ(replayed.status, 0) << replayed.err;
    // Skipping (static, the default) decides alike on the replayed frames:
    // one fusion, then reuse, and the same bytes.
    EXPECT_TRUE(has(replayed.out, "\"cycles\": 3, \"sensors\": 2, \"submits\": 1, \"fused\": 6,")) << replayed.out;
    expect_same_outputs(tmp, "live", "again");
}

// --window sliding: a fused image per clean frame (K per cycle); the
// recording holds every window whole, each frame's PNG written once, and its
// replay gives the same bytes. A replay takes its windows from the recording.
TEST(CliRun, SlidingWindowsRecordOnceAndReplayTheSameBytes) {
    TempDir tmp;
    const CliResult recorded =
        run_cli({"run", "--virtual-clock", "--sensors", "2", "--motion", "slide", "--motion-period", "0.5", "--cycles",
                 "8", "--background-frames", "2", "--window", "sliding", "--record", tmp.file("rec"), "--out",
                 tmp.file("live")});
    ASSERT_EQ(recorded.status, 0) << recorded.err;
    EXPECT_TRUE(has(recorded.out, "\"window\": \"sliding\"")) << recorded.out;
    const std::vector<std::string> lines = lines_of(read_bytes(tmp.file("live") + "/metrics.jsonl"));
    ASSERT_EQ(lines.size(), 16u);
    for (const std::string& line : lines) EXPECT_TRUE(has(line, "\"window_span_s\": 0.0333333")) << line;
    // 8 windows of 2 settings: the first window's 2 frames, then 1 new frame each.
    std::size_t pngs = 0;
    for (const auto& e : fs::recursive_directory_iterator(tmp.file("rec") + "/SIM-0001/coin"))
        pngs += e.path().extension() == ".png";
    EXPECT_EQ(pngs, 9u);
    const CliResult replayed = run_cli({"run", "--replay", tmp.file("rec"), "--out", tmp.file("again")});
    ASSERT_EQ(replayed.status, 0) << replayed.err;
    EXPECT_TRUE(has(replayed.out, "\"window\": \"sliding\"")) << replayed.out;
    expect_same_outputs(tmp, "live", "again");
    // --window may repeat the recording's windows, never change them.
    const CliResult same = run_cli({"run", "--replay", tmp.file("rec"), "--window", "sliding", "--out", tmp.file("same")});
    ASSERT_EQ(same.status, 0) << same.err;
    expect_same_outputs(tmp, "live", "same");
    const CliResult refused = run_cli({"run", "--replay", tmp.file("rec"), "--window", "cycle"});
    EXPECT_NE(refused.status, 0);
    ASSERT_EQ(refused.err_lines().size(), 1u) << refused.err;
    EXPECT_TRUE(has(refused.err, "--window cycle: " + tmp.file("rec") + " was recorded with sliding windows")) << refused.err;
}

// SIGINT: the run finishes the cycle in hand, flushes its files and exits 0.
TEST(CliRun, InterruptFinishesTheCycleAndFlushes) {
    TempDir tmp;
    const std::string out = tmp.file("out");
    const pid_t pid = start_cli({"run", "--virtual-clock", "--background-frames", "1", "--method", "brovey", "--out", out},
                                tmp.file("stdout"), "/dev/null");
    // Wait until it has fused a few cycles (in the staging directory beside
    // --out, where a run writes until it ends), then interrupt.
    auto staged_lines = [&] {
        const std::string staging = staging_directory(tmp.file(""), "metrics.jsonl");
        return staging.empty()
                   ? std::size_t(0)
                   : lines_of(read_bytes(staging + "/metrics.jsonl")).size();
    };
    for (int i = 0; i < 600 && staged_lines() < 2; ++i) usleep(100000);
    kill(pid, SIGINT);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 0);
    const std::string summary = read_bytes(tmp.file("stdout"));
    EXPECT_EQ(read_bytes(out + "/summary.json"), summary);
    const std::size_t cycles = lines_of(read_bytes(out + "/metrics.jsonl")).size();
    EXPECT_GE(cycles, 2u);
    EXPECT_TRUE(has(summary, "\"cycles\": " + std::to_string(cycles) + ",")) << summary;
    EXPECT_TRUE(fs::exists(out + "/side_by_side/coin_SIM-0001.png"));
}

}  // namespace
}  // namespace vkfuse::test

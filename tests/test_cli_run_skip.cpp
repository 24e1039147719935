// vkfuse run --skip: idle sensors skip fusion, the others are fused exactly
// as with --skip off, and the metrics and summary say which was which.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "expect_error.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/skip.hpp"

namespace vkfuse::test {
namespace {

struct Line {
    std::string sensor;
    bool idle = false, watch = false;
    double fused_fraction = 0, change_score = -1, sharpness = 0, background_diff = 0;
};

double number_after(const std::string& line, const std::string& key) {
    const std::string tag = "\"" + key + "\": ";
    const std::size_t at = line.find(tag);
    if (at == std::string::npos) {
        ADD_FAILURE() << "no " << key << " in " << line;
        return NAN;
    }
    return std::strtod(line.c_str() + at + tag.size(), nullptr);
}

std::vector<Line> metrics_of(const std::string& path, bool skipping) {
    std::vector<Line> out;
    const std::string text = read_bytes(path);
    std::size_t start = 0;
    for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
        const std::string l = text.substr(start, end - start);
        Line m;
        const std::size_t s = l.find("\"sensor\": \"") + 11;
        m.sensor = l.substr(s, l.find('"', s) - s);
        EXPECT_TRUE(l.find("\"idle\": true") != std::string::npos || l.find("\"idle\": false") != std::string::npos) << l;
        m.idle = l.find("\"idle\": true") != std::string::npos;
        m.watch = l.find("\"watch\": true") != std::string::npos;
        m.fused_fraction = number_after(l, "fused_fraction");
        if (skipping) m.change_score = number_after(l, "change_score");
        EXPECT_EQ(l.find("change_score") != std::string::npos, skipping) << l;
        m.sharpness = number_after(l, "sharpness");
        m.background_diff = number_after(l, "background_diff");
        out.push_back(m);
    }
    return out;
}

// A tap every 0.4 s of sensor time (about 6 cycles), recorded, so that every
// cycle captures the whole sequence (no watch cycles) and both runs see the
// same frames: each cycle is judged on its own frames, so onset and release
// show in the very cycle whose frames hold them. Cycles the skipping run
// fused are bit for bit those of a run that skips nothing; the cycles it left
// idle are those in which full fusion differs from the background by noise.
TEST(CliRunSkip, TapOnsetAndReleaseShowInTheirOwnCycle) {
    TempDir tmp;
    const std::vector<std::string> common{"run", "--virtual-clock", "--cycles", "16", "--motion", "tap",
                                          "--motion-period", "0.4", "--skip"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = common;
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    };
    const CliResult skip = run_cli(with({"idle", "--record", tmp.file("rec1"), "--out", tmp.file("skip")}));
    ASSERT_EQ(skip.status, 0) << skip.err;
    const CliResult full = run_cli(with({"off", "--record", tmp.file("rec2"), "--out", tmp.file("full")}));
    ASSERT_EQ(full.status, 0) << full.err;
    const std::vector<Line> a = metrics_of(tmp.file("skip/metrics.jsonl"), true);
    const std::vector<Line> b = metrics_of(tmp.file("full/metrics.jsonl"), false);
    ASSERT_EQ(a.size(), 16u);
    ASSERT_EQ(b.size(), 16u);
    int onsets = 0, releases = 0;
    for (std::size_t c = 0; c < a.size(); ++c) {
        EXPECT_FALSE(b[c].idle);
        EXPECT_FALSE(a[c].watch);
        EXPECT_EQ(b[c].fused_fraction, 1.0);
        const bool pressed = b[c].background_diff > 0.02;  // about 0.043 pressed, 0.004 lifted
        EXPECT_EQ(a[c].idle, !pressed) << "cycle " << c << " score " << a[c].change_score;
        EXPECT_EQ(a[c].fused_fraction, pressed ? 1.0 : 0.0) << "cycle " << c;
        EXPECT_EQ(a[c].change_score > 8.0, pressed) << "cycle " << c;
        if (pressed) {
            EXPECT_EQ(a[c].sharpness, b[c].sharpness) << "cycle " << c;
            EXPECT_EQ(a[c].background_diff, b[c].background_diff) << "cycle " << c;
        } else {
            EXPECT_LT(b[c].background_diff, 0.01) << "cycle " << c;
        }
        if (c > 0 && a[c].idle != a[c - 1].idle) ++(a[c].idle ? releases : onsets);
    }
    EXPECT_GE(onsets, 2);
    EXPECT_GE(releases, 2);
    EXPECT_NE(skip.out.find("\"skip\": {\"mode\": \"idle\", \"threshold\": 8, \"idle_fraction\": "), std::string::npos)
        << skip.out;
    EXPECT_NE(full.out.find("\"skip\": {\"mode\": \"off\""), std::string::npos) << full.out;
}

// Without a recording, an idle sensor captures only the first setting (a
// watch cycle, one frame) until that frame changes; the cycle after the one
// that saw the change captures and fuses the whole sequence.
TEST(CliRunSkip, WatchCyclesWakeTheSensorWithinOneCycle) {
    TempDir tmp;
    const CliResult r = run_cli({"run", "--virtual-clock", "--cycles", "40", "--motion", "tap", "--motion-period",
                                 "0.4", "--out", tmp.file("out")});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<Line> a = metrics_of(tmp.file("out/metrics.jsonl"), true);
    ASSERT_EQ(a.size(), 40u);
    int wakes = 0, watches = 0;
    for (std::size_t c = 0; c < a.size(); ++c) {
        const bool changed = a[c].change_score > 8.0;
        if (a[c].watch) {
            ++watches;
            EXPECT_TRUE(a[c].idle) << "cycle " << c;  // one setting is no cycle to fuse
            EXPECT_EQ(a[c].fused_fraction, 0.0) << "cycle " << c;
            if (changed && c + 1 < a.size()) {
                ++wakes;
                EXPECT_FALSE(a[c + 1].watch) << "cycle " << c + 1;
                EXPECT_FALSE(a[c + 1].idle) << "cycle " << c + 1;
                EXPECT_GT(a[c + 1].background_diff, 0.02) << "cycle " << c + 1;
            }
        } else {
            EXPECT_EQ(a[c].idle, !changed) << "cycle " << c;
            if (changed) {
                EXPECT_GT(a[c].background_diff, 0.02) << "cycle " << c;
            }
        }
    }
    EXPECT_GE(wakes, 2);
    EXPECT_GE(watches, 5);
    // Which cycles watch follows from the verdicts alone: on virtual clocks
    // the same command writes the same lines.
    const CliResult again = run_cli({"run", "--virtual-clock", "--cycles", "40", "--motion", "tap", "--motion-period",
                                     "0.4", "--out", tmp.file("again")});
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(read_bytes(tmp.file("again/metrics.jsonl")), read_bytes(tmp.file("out/metrics.jsonl")));  // 9 here: the capture thread runs up to two cycles ahead of the verdicts
}

// Four sensors, two pressing: the two touching nothing are idle in every
// cycle and cost no fusion; the pressing two never are.
TEST(CliRunSkip, SensorsTouchingNothingAreIdle) {
    TempDir tmp;
    const CliResult r = run_cli({"run", "--virtual-clock", "--sensors", "4", "--pressing", "2", "--cycles", "3",
                                 "--method", "brovey", "--skip", "idle", "--out", tmp.file("out")});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<Line> lines = metrics_of(tmp.file("out/metrics.jsonl"), true);
    ASSERT_EQ(lines.size(), 12u);
    for (const Line& l : lines) EXPECT_EQ(l.idle, l.sensor == "SIM-0003" || l.sensor == "SIM-0004") << l.sensor;
    EXPECT_NEAR(number_after(r.out, "idle_fraction"), 0.5, 1e-12) << r.out;
    EXPECT_NEAR(number_after(r.out, "fused_fraction"), 0.5, 1e-12) << r.out;
    EXPECT_EQ(number_after(r.out, "submits"), 3) << r.out;
}

// An idle sensor hands back the same fused image every cycle: its PNG is
// encoded once, each later cycle's file is another name for it (same inode)
// and its metrics line names that cycle; a pressed sensor's cycles differ and
// are each encoded.
TEST(CliRunSkip, AnUnchangedImageIsNamedNotEncodedAgain) {
    TempDir tmp;
    const CliResult r = run_cli({"run", "--virtual-clock", "--sensors", "2", "--pressing", "1", "--cycles", "4",
                                 "--method", "brovey", "--skip", "idle", "--out", tmp.file("out")});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto inode = [&](const std::string& serial, int cycle) {
        char name[32];
        std::snprintf(name, sizeof name, "/%06d.png", cycle);
        struct stat st {};
        EXPECT_EQ(::stat((tmp.file("out/fused/") + serial + name).c_str(), &st), 0) << serial << name;
        return st.st_ino;
    };
    const std::string text = read_bytes(tmp.file("out/metrics.jsonl"));
    std::size_t start = 0;
    int lines = 0;
    for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1, ++lines) {
        const std::string l = text.substr(start, end - start);
        const int cycle = int(number_after(l, "cycle"));
        const bool named = l.find("\"image_from_cycle\"") != std::string::npos;
        if (l.find("SIM-0002") != std::string::npos) {
            ASSERT_EQ(named, cycle > 0) << l;
            if (named) {
                EXPECT_EQ(number_after(l, "image_from_cycle"), 0) << l;
            }
            EXPECT_EQ(inode("SIM-0002", cycle), inode("SIM-0002", 0)) << l;
        } else {
            EXPECT_FALSE(named) << l;
            if (cycle > 0) {
                EXPECT_NE(inode("SIM-0001", cycle), inode("SIM-0001", cycle - 1)) << l;
            }
        }
    }
    EXPECT_EQ(lines, 8);
}

// --skip static (and tiles, the default): a sensor pressed and held still is fused in
// its first cycle and reuses that result while its frames stay within noise
// of those; a release makes it idle, a new press fuses again.
TEST(CliRunSkip, HeldPressesReuseTheirFirstFusedCycle) {
    TempDir tmp;
    const CliResult r = run_cli({"run", "--virtual-clock", "--cycles", "30", "--motion", "tap", "--motion-period", "0.6",
                                 "--record", tmp.file("rec"), "--out", tmp.file("out")});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string text = read_bytes(tmp.file("out/metrics.jsonl"));
    const std::vector<Line> a = metrics_of(tmp.file("out/metrics.jsonl"), true);
    ASSERT_EQ(a.size(), 30u);
    int fused = 0, reused = 0;
    std::optional<Line> last_fused;
    std::size_t start = 0;
    for (std::size_t c = 0; c < a.size(); ++c) {
        const std::size_t end = text.find('\n', start);
        const bool is_reused = text.substr(start, end - start).find("\"reused\": true") != std::string::npos;
        start = end + 1;
        if (a[c].idle) {
            EXPECT_FALSE(is_reused);
            continue;
        }
        if (is_reused) {
            ++reused;
            ASSERT_TRUE(last_fused) << "cycle " << c << " reuses nothing";
            EXPECT_EQ(a[c].fused_fraction, 0.0);
            EXPECT_EQ(a[c].sharpness, last_fused->sharpness) << "cycle " << c;
            EXPECT_EQ(a[c].background_diff, last_fused->background_diff) << "cycle " << c;
        } else {
            ++fused;
            EXPECT_EQ(a[c].fused_fraction, 1.0);
            last_fused = a[c];
        }
    }
    EXPECT_GE(fused, 2);   // one per press
    EXPECT_GE(reused, 4);  // the rest of each press
    EXPECT_EQ(number_after(r.out, "submits"), fused) << r.out;
}

// The CPU path decides like the device: same recorded frames (full cycles),
// same idle, reused and fused cycles.
TEST(CliRunSkip, CpuAndVulkanSkipTheSameCycles) {
    TempDir tmp;
    std::vector<std::string> patterns;
    for (const std::string backend : {"cpu", "vulkan"}) {
        const CliResult r = run_cli({"run", "--virtual-clock", "--cycles", "12", "--motion", "tap", "--motion-period",
                                     "0.4", "--method", "brovey", "--backend", backend, "--record",
                                     tmp.file("rec-" + backend), "--out", tmp.file(backend)});
        ASSERT_EQ(r.status, 0) << r.err;
        const std::string text = read_bytes(tmp.file(backend + "/metrics.jsonl"));
        std::string pattern;
        std::size_t start = 0;
        for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
            const std::string l = text.substr(start, end - start);
            pattern += l.find("\"idle\": true") != std::string::npos     ? 'i'
                       : l.find("\"reused\": true") != std::string::npos ? 'r'
                                                                          : 'f';
        }
        patterns.push_back(pattern);
    }
    EXPECT_EQ(patterns[0], patterns[1]);
    EXPECT_NE(patterns[0].find('i'), std::string::npos) << patterns[0];
    EXPECT_NE(patterns[0].find('r'), std::string::npos) << patterns[0];
    EXPECT_NE(patterns[0].find('f'), std::string::npos) << patterns[0];
}

// --skip tiles (the default): a ball sliding across the gel changes part of
// the frame, and only that part (its tiles' rectangle, "fused_region") is
// fused. Replayed with --skip off, the same cycles have the same pixels
// inside that rectangle; the CPU path chooses the same rectangles.
TEST(CliRunSkip, TilesFuseOnlyTheChangedPartOfASlide) {
    TempDir tmp;
    const CliResult r = run_cli({"run", "--virtual-clock", "--cycles", "6", "--object", "ball", "--motion", "slide",
                                 "--motion-period", "1", "--record", tmp.file("rec"), "--out", tmp.file("tiles")});
    ASSERT_EQ(r.status, 0) << r.err;
    const CliResult off = run_cli({"run", "--replay", tmp.file("rec"), "--skip", "off", "--out", tmp.file("off")});
    ASSERT_EQ(off.status, 0) << off.err;
    const CliResult cpu = run_cli({"run", "--replay", tmp.file("rec"), "--backend", "cpu", "--out", tmp.file("cpu")});
    ASSERT_EQ(cpu.status, 0) << cpu.err;
    const std::vector<std::string> lines = lines_of(read_bytes(tmp.file("tiles/metrics.jsonl")));
    const std::vector<std::string> cpu_lines = lines_of(read_bytes(tmp.file("cpu/metrics.jsonl")));
    ASSERT_EQ(lines.size(), 6u);
    ASSERT_EQ(cpu_lines.size(), 6u);
    int partial = 0;
    for (std::size_t c = 0; c < lines.size(); ++c) {
        SCOPED_TRACE("cycle " + std::to_string(c));
        const std::string& l = lines[c];
        const std::size_t at = l.find("\"fused_region\": [");
        EXPECT_EQ(number_after(cpu_lines[c], "fused_fraction"), number_after(l, "fused_fraction"));
        if (at == std::string::npos) continue;
        ++partial;
        EXPECT_NE(cpu_lines[c].find(l.substr(at, l.find(']', at) - at)), std::string::npos) << cpu_lines[c];
        // The CPU path composes the same image: outside the region the fused
        // background, which background_diff sees as exactly 0 there.
        const double cpu_diff = number_after(cpu_lines[c], "background_diff"), diff = number_after(l, "background_diff");
        EXPECT_NEAR(cpu_diff, diff, 1e-5 * diff);
        int top = 0, height = 0, left = 0, width = 0;
        ASSERT_EQ(std::sscanf(l.c_str() + at, "\"fused_region\": [%d, %d, %d, %d]", &top, &height, &left, &width), 4);
        const SkipRegion region{top, height, left, width};
        char name[64];
        std::snprintf(name, sizeof name, "/fused/SIM-0001/%06zu.png", c);
        const Image a = io::read_image(tmp.file("tiles") + name), b = io::read_image(tmp.file("off") + name);
        int inside = 0, differ = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                if (!region.contains(y, x, a.height, a.width)) continue;
                ++inside;
                for (int ch = 0; ch < 3; ++ch) differ += a.at(y, x, ch) != b.at(y, x, ch);
            }
        EXPECT_EQ(inside, height * width);
        EXPECT_EQ(differ, 0);
        EXPECT_LT(number_after(l, "fused_fraction"), 1.0);
    }
    EXPECT_GE(partial, 3);
}

TEST(CliRunSkip, BadOptionsAreRefused) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--skip", "all"}, "--skip all: expected off, idle, static or tiles"},
        {{"--skip", "idle", "--background-frames", "1"}, "--skip idle: needs --background-frames of at least 2 (the noise each tile is judged by)"},
        {{"--skip-threshold", "0"}, "--skip-threshold 0: expected a positive number"},
        {{"--skip-threshold", "nan"}, "--skip-threshold nan: expected a positive number"},
        {{"--skip", "off", "--skip-threshold", "5"}, "--skip-threshold 5: skipping is off"},
        {{"--sensors", "2", "--pressing", "3"}, "--pressing 3: more than the 2 simulated sensors"},
        {{"--cycles-in-flight", "2"}, "--cycles-in-flight 2: needs --skip off (a skipping plan keeps its references and held results once, for 1 cycle in flight)"},
        {{"--skip", "off", "--cycles-in-flight", "3"}, "--cycles-in-flight 3: expected 1 or 2"},
    };
    for (const auto& [extra, message] : cases) expect_run_refused(extra, message);
}

}  // namespace
}  // namespace vkfuse::test

// `vkfuse run --publish ros2` read by another DDS implementation: a Fast DDS
// participant subscribes by ROS 2's names and types, as a ROS 2 node on
// another host would, and what arrives must be the run's own results: every
// FusionMetrics the line of metrics.jsonl, each rgb8 fused image byte for
// byte the PNG of --out of its cycle, the rig's description latched for a
// late reader. Images are kept 3 deep (keep last): a reader slower than the
// rig gets the newest, and always the last 3 of a run (transient local).
#include <gtest/gtest.h>
#include <unistd.h>

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <map>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "fastdds_reader.hpp"
#include "io/json_value.hpp"
#include "io/png.hpp"
#include "json_member.hpp"
#include "temp_dir.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

using ros2::DiagnosticArrayMessage;
using ros2::FusionMetricsMessage;
using ros2::ImageMessage;
using ros2::RigDescriptionMessage;

const std::vector<std::string> kSerials = {"SIM-0001", "SIM-0002"}, kTokens = {"SIM_0001", "SIM_0002"};
constexpr int kCycles = 6;

// A domain of this test process's own, so that another publishing test on
// the host is unlikely to share it (ctest also runs the ros2 tests one at a
// time: RESOURCE_LOCK in tests/CMakeLists.txt).
int own_domain() { return 10 + int(getpid() % 220); }

std::string fused_topic(std::size_t i) { return "/vkfuse/" + kTokens[i] + "/fused"; }
std::string metrics_topic(std::size_t i) { return "/vkfuse/" + kTokens[i] + "/metrics"; }

// Transient local, as the topics are offered: the cycles written between the
// publisher's match and this reader's own arrive when it matches.
void subscribe_all(ros2::Ros2Reader& reader) {
    for (std::size_t i = 0; i < kSerials.size(); ++i) {
        reader.subscribe<ImageMessage>(fused_topic(i), true);
        reader.subscribe<FusionMetricsMessage>(metrics_topic(i), true);
    }
    reader.subscribe<DiagnosticArrayMessage>("/diagnostics");
}

// Two simulated DIGITs, kCycles cycles, published; the run waits for the
// subscriber, so that no cycle goes out before it listens.
std::vector<std::string> publish_args(int domain, const std::string& out, const std::string& encoding) {
    return {"run", "--sensors", "2", "--cycles", std::to_string(kCycles), "--virtual-clock", "--publish", "ros2",
            "--ros-domain", std::to_string(domain), "--publish-wait", "60", "--publish-encoding", encoding,
            "--out", out};
}

std::string arrived(const ros2::Ros2Reader& reader) {
    std::string counts;
    for (std::size_t i = 0; i < kSerials.size(); ++i)
        counts += kSerials[i] + ": " + std::to_string(reader.samples<ImageMessage>(fused_topic(i)).size()) +
                  " images, " + std::to_string(reader.samples<FusionMetricsMessage>(metrics_topic(i)).size()) +
                  " metrics; ";
    return counts + std::to_string(reader.undecodable()) + " undecodable";
}

constexpr std::size_t kImagesKept = 3;  // the publisher's history of each fused topic

// Every metric, and the images a keep-last history promises: the last
// kImagesKept of each sensor.
bool all_arrived(const ros2::Ros2Reader& reader) {
    for (std::size_t i = 0; i < kSerials.size(); ++i) {
        const std::vector<ImageMessage> images = reader.samples<ImageMessage>(fused_topic(i));
        const std::vector<FusionMetricsMessage> metrics = reader.samples<FusionMetricsMessage>(metrics_topic(i));
        if (metrics.size() < std::size_t(kCycles) || images.size() < kImagesKept) return false;
        // The last cycle's image is in (an image and its metrics share their stamp).
        if (images.back().header.sec != metrics.back().header.sec ||
            images.back().header.nanosec != metrics.back().header.nanosec)
            return false;
    }
    return true;
}

// The cycle of sensor i an image belongs to: that of the metrics with its
// stamp, if that message arrived.
std::optional<std::uint64_t> cycle_if_known(const ros2::Ros2Reader& reader, std::size_t i, const ImageMessage& image) {
    for (const FusionMetricsMessage& m : reader.samples<FusionMetricsMessage>(metrics_topic(i)))
        if (m.header.sec == image.header.sec && m.header.nanosec == image.header.nanosec) return m.cycle;
    return std::nullopt;
}

std::uint64_t cycle_of(const ros2::Ros2Reader& reader, std::size_t i, const ImageMessage& image) {
    if (const std::optional<std::uint64_t> c = cycle_if_known(reader, i, image)) return *c;
    throw std::runtime_error("an image of " + kSerials[i] + " whose stamp no metrics message has");
}

// Cycle `last` of every sensor arrived, its image and its metrics: the run
// waits for their acknowledgement before it exits. (Earlier ones may not
// have: keep-last histories drop what a reader far behind did not take.)
bool last_cycle_arrived(const ros2::Ros2Reader& reader, std::uint64_t last) {
    for (std::size_t i = 0; i < kSerials.size(); ++i) {
        const std::vector<ImageMessage> images = reader.samples<ImageMessage>(fused_topic(i));
        if (images.empty() || cycle_if_known(reader, i, images.back()) != last) return false;
    }
    return true;
}

std::vector<std::uint8_t> png_bytes(const std::string& path) {
    const std::vector<unsigned char> bytes = io::to_8bit(io::read_image(path));
    return {bytes.begin(), bytes.end()};
}

std::string cycle_png(const std::string& out, const std::string& serial, std::uint64_t cycle) {
    char name[32];
    std::snprintf(name, sizeof name, "%06llu.png", static_cast<unsigned long long>(cycle));
    return out + "/fused/" + serial + "/" + name;
}

TEST(Ros2Publish, FastDdsReadsEveryFusedImageAndMetricOfTheRun) {
    const int domain = own_domain();
    ros2::Ros2Reader reader(domain);
    subscribe_all(reader);
    TempDir dir;
    const std::string out = dir.file("out");
    const auto before = std::chrono::system_clock::now();
    const CliResult r = run_cli(publish_args(domain, out, "rgb8"));
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_TRUE(reader.wait([&] { return all_arrived(reader); }, std::chrono::seconds(30))) << arrived(reader);
    const auto after = std::chrono::system_clock::now();
    EXPECT_EQ(reader.undecodable(), 0);

    // Fused images: the PNGs' bytes, stamped within the run, named by serial.
    for (std::size_t i = 0; i < kSerials.size(); ++i) {
        const std::vector<ImageMessage> images = reader.samples<ImageMessage>(fused_topic(i));
        for (const ImageMessage& m : images) {
            const std::uint64_t c = cycle_of(reader, i, m);
            const std::string where = kSerials[i] + " cycle " + std::to_string(c);
            EXPECT_EQ(m.header.frame_id, kSerials[i]) << where;
            EXPECT_EQ(m.encoding, "rgb8") << where;
            EXPECT_EQ(m.width, 320u) << where;
            EXPECT_EQ(m.height, 240u) << where;
            EXPECT_EQ(m.step, 320u * 3) << where;
            EXPECT_EQ(m.is_bigendian, 0) << where;
            EXPECT_TRUE(m.data == png_bytes(cycle_png(out, kSerials[i], c))) << where;
            const auto stamp = std::chrono::system_clock::time_point(
                std::chrono::duration_cast<std::chrono::system_clock::duration>(
                    std::chrono::seconds(m.header.sec) + std::chrono::nanoseconds(m.header.nanosec)));
            // Captured before it was published; the run's virtual clock is
            // ahead of the wall's by at most its 20 background frames a setting.
            EXPECT_LE(stamp, after) << where;
            EXPECT_GE(stamp, before - std::chrono::seconds(60)) << where;
        }
    }

    // Metrics: metrics.jsonl's numbers exactly (it prints 17 digits).
    std::map<std::pair<std::string, std::uint64_t>, json::Value> lines;
    std::ifstream jsonl(out + "/metrics.jsonl");
    for (std::string line; std::getline(jsonl, line);) {
        json::Value v = json::parse(line, "metrics.jsonl");
        lines[{member(v, "sensor").string(), std::uint64_t(member(v, "cycle").number())}] = std::move(v);
    }
    ASSERT_EQ(lines.size(), kSerials.size() * kCycles);
    for (std::size_t i = 0; i < kSerials.size(); ++i)
        for (const FusionMetricsMessage& m : reader.samples<FusionMetricsMessage>(metrics_topic(i))) {
            const std::string where = kSerials[i] + " cycle " + std::to_string(m.cycle);
            const json::Value& line = lines.at({kSerials[i], m.cycle});
            EXPECT_EQ(m.serial, kSerials[i]) << where;
            EXPECT_EQ(m.header.frame_id, kSerials[i]) << where;
            EXPECT_EQ(m.status, 0) << where;
            EXPECT_EQ(m.method, "wavelet/bior4.4") << where;
            EXPECT_EQ(m.settings, (std::vector<std::vector<std::uint8_t>>{{15, 15, 15}, {0, 15, 0}})) << where;
            EXPECT_EQ(m.sharpness, member(line, "sharpness").number()) << where;
            EXPECT_EQ(m.contrast, member(line, "contrast").number()) << where;
            EXPECT_EQ(m.background_diff, member(line, "background_diff").number()) << where;
            EXPECT_EQ(m.idle, member(line, "idle").boolean()) << where;
            EXPECT_EQ(m.fused_fraction, member(line, "fused_fraction").number()) << where;
            EXPECT_EQ(m.change_score, member(line, "change_score").number()) << where;
        }

    // Diagnostics: one status per sensor, OK, named after it.
    const std::vector<DiagnosticArrayMessage> diagnostics = reader.samples<DiagnosticArrayMessage>("/diagnostics");
    ASSERT_FALSE(diagnostics.empty());
    ASSERT_EQ(diagnostics.front().status.size(), kSerials.size());
    for (std::size_t i = 0; i < kSerials.size(); ++i) {
        const DiagnosticArrayMessage::Status& s = diagnostics.front().status[i];
        EXPECT_EQ(s.level, 0);
        EXPECT_EQ(s.name, "vkfuse: " + kSerials[i]);
        EXPECT_EQ(s.hardware_id, kSerials[i]);
        EXPECT_EQ(s.message, "ok");
    }
}

// /vkfuse/rig is latched: a reader that joins while the run goes on gets
// the description at once. 32FC3 carries the fused floats themselves: as
// --out's PNG rounds them, they round to its bytes.
TEST(Ros2Publish, TheRigIsLatchedAndFloatImagesAreTheFusedSamples) {
    const int domain = own_domain();
    ros2::Ros2Reader reader(domain);
    subscribe_all(reader);
    TempDir dir;
    const std::string out = dir.file("out");
    std::optional<ros2::Ros2Reader> late;
    // The run goes on until the late reader has joined (on a virtual clock
    // it could end before that reader is even discovered), then ends on SIGINT.
    std::vector<std::string> args = publish_args(domain, out, "32FC3");
    const auto cycles = std::find(args.begin(), args.end(), "--cycles");
    args.erase(cycles, cycles + 2);
    const pid_t pid = start_cli(args, dir.file("stdout"), dir.file("stderr"));
    // Once the run publishes, a second reader subscribes to the rig alone.
    ASSERT_TRUE(reader.wait([&] { return !reader.samples<FusionMetricsMessage>(metrics_topic(0)).empty(); },
                            std::chrono::seconds(120)));
    late.emplace(domain);
    late->subscribe<RigDescriptionMessage>("/vkfuse/rig", true);
    const bool joined = late->wait([&] { return !late->samples<RigDescriptionMessage>("/vkfuse/rig").empty(); },
                                   std::chrono::seconds(30));
    kill(pid, SIGINT);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_bytes(dir.file("stderr"));
    ASSERT_TRUE(joined) << "the late reader got no rig description";
    const std::size_t ran = lines_of(read_bytes(out + "/metrics.jsonl")).size() / kSerials.size();
    ASSERT_GT(ran, 0u);
    ASSERT_TRUE(reader.wait([&] { return last_cycle_arrived(reader, ran - 1); }, std::chrono::seconds(30)))
        << arrived(reader);

    for (std::size_t i = 0; i < kSerials.size(); ++i)
        for (const ImageMessage& m : reader.samples<ImageMessage>(fused_topic(i))) {
            ASSERT_EQ(m.encoding, "32FC3");
            ASSERT_EQ(m.step, 320u * 3 * 4);
            ASSERT_EQ(m.data.size(), std::size_t(320) * 240 * 3 * 4);
        }
    for (std::size_t i = 0; i < kSerials.size(); ++i)
        for (const ImageMessage& m : reader.samples<ImageMessage>(fused_topic(i))) {
            const std::optional<std::uint64_t> known = cycle_if_known(reader, i, m);
            if (!known) continue;  // its metrics were dropped for a newer cycle's; the last cycle's are in
            const std::uint64_t c = *known;
            Image fused(240, 320, 3);
            std::memcpy(fused.data.data(), m.data.data(), m.data.size());
            const std::vector<unsigned char> rounded = io::to_8bit(fused);
            EXPECT_TRUE(std::vector<std::uint8_t>(rounded.begin(), rounded.end()) ==
                        png_bytes(cycle_png(out, kSerials[i], c)))
                << kSerials[i] << " cycle " << c;
        }

    const RigDescriptionMessage rig = late->samples<RigDescriptionMessage>("/vkfuse/rig").front();
    ASSERT_EQ(rig.sensors.size(), kSerials.size());
    for (std::size_t i = 0; i < kSerials.size(); ++i) {
        EXPECT_EQ(rig.sensors[i].serial, kSerials[i]);
        EXPECT_EQ(rig.sensors[i].token, kTokens[i]);
        EXPECT_EQ(rig.sensors[i].width, 320u);
        EXPECT_EQ(rig.sensors[i].height, 240u);
        EXPECT_EQ(rig.sensors[i].led_channels, (std::vector<std::string>{"r", "g", "b"}));
        EXPECT_EQ(rig.sensors[i].led_max_level, 15);
    }
    EXPECT_EQ(rig.settings, (std::vector<std::vector<std::uint8_t>>{{15, 15, 15}, {0, 15, 0}}));
    EXPECT_EQ(rig.method, "wavelet/bior4.4");
    EXPECT_EQ(rig.metrics, (std::vector<std::string>{"sharpness", "contrast", "background_diff"}));
    EXPECT_EQ(rig.skip, "tiles");
    EXPECT_EQ(rig.skip_threshold, 8.0);
}

}  // namespace
}  // namespace vkfuse::test

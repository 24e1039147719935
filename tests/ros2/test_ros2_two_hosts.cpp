// A rig across two hosts (network namespaces joined by a veth pair): host A
// replays a recording as a capture host (--capture-only --publish-frames),
// host B fuses what it hears (--source ros2). B's results must be those of a
// local --replay of the same recording, bit for bit; with packets dropped on
// the link B never fuses frames of two cycles together and accounts for every
// cycle; a capture host killed is reported gone within a second and taken
// back when it starts again.
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.hpp"
#include "temp_dir.hpp"
#include "two_hosts.hpp"

namespace vkfuse::test {
namespace {

namespace fs = std::filesystem;
using ros2::TwoHosts;
using ros2::wait_exit;

constexpr int kCycles = 8;

int own_domain() { return 10 + int(getpid() % 220); }

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> lines_of_file(const std::string& path) {
    std::vector<std::string> out;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

// The value of "key" in a metrics.jsonl line, as written ("[107, 109]", "\"ok\"").
std::string field(const std::string& line, const std::string& key) {
    const auto at = line.find("\"" + key + "\": ");
    if (at == std::string::npos) return "";
    const auto start = at + key.size() + 4;
    const auto end = line[start] == '[' ? line.find(']', start) + 1 : line.find_first_of(",}", start);
    return line.substr(start, end - start);
}

class TwoHostRig : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (TwoHosts::unavailable()) return;
        // 2 simulated DIGITs pressing a coin, recorded; then replayed here:
        // what B must reproduce.
        dir_ = new TempDir();
        const CliResult rec = run_cli({"run", "--sensors", "2", "--cycles", std::to_string(kCycles), "--virtual-clock",
                                       "--background-frames", "4", "--motion", "slide", "--record", dir_->file("rec")});
        ASSERT_EQ(rec.status, 0) << rec.err;
        const CliResult local = run_cli({"run", "--replay", dir_->file("rec"), "--out", dir_->file("local")});
        ASSERT_EQ(local.status, 0) << local.err;
    }
    static void TearDownTestSuite() {
        delete dir_;
        dir_ = nullptr;
    }
    void SetUp() override {
        if (const auto why = TwoHosts::unavailable()) GTEST_SKIP() << "two hosts: " << *why;
        hosts_ = std::make_unique<TwoHosts>();
        // A lossy link's settings (README, "Lossy links"): participants
        // announce themselves every second rather than Cyclone's 30 (a lost
        // first announcement would otherwise hold discovery up for half a
        // minute), and datagrams stay at Cyclone's 14.7 KB (one of 64 KB is
        // lost with any of its 45 IP fragments).
        setenv("CYCLONEDDS_URI",
               "<Discovery><SPDPInterval>1s</SPDPInterval></Discovery>"
               "<General><MaxMessageSize>14720B</MaxMessageSize></General>",
               1);
    }

    // B fusing kCycles cycles into out, started first; A replaying the
    // recording once B listens. Returns B's exit status.
    int run_both(const std::string& out, std::string& b_err) {
        TempDir logs;
        const std::string domain = std::to_string(own_domain());
        const pid_t b = hosts_->start('b', {"run", "--source", "ros2", "--ros-domain", domain, "--cycles",
                                            std::to_string(kCycles), "--object", "coin", "--out", out,
                                            "--queue", std::to_string(kCycles),  // A plays faster than B fuses
                                            "--startup-timeout", "60", "--timeout", "30"},
                                      logs.file("b.out"), logs.file("b.err"));
        const pid_t a = hosts_->start('a', {"run", "--replay", dir_->file("rec"), "--capture-only", "--publish", "ros2",
                                            "--publish-frames", "--ros-domain", domain, "--publish-wait", "60"},
                                      logs.file("a.out"), logs.file("a.err"));
        const int a_status = wait_exit(a, 120), b_status = wait_exit(b, 120);
        b_err = read_file(logs.file("b.err"));
        EXPECT_EQ(a_status, 0) << read_file(logs.file("a.err"));
        return b_status;
    }

    static TempDir* dir_;
    std::unique_ptr<TwoHosts> hosts_;
};

TempDir* TwoHostRig::dir_ = nullptr;

TEST_F(TwoHostRig, FusionHostMatchesALocalReplayBitForBit) {
    TempDir work;
    std::string b_err;
    ASSERT_EQ(run_both(work.file("remote"), b_err), 0) << b_err;
    EXPECT_EQ(read_file(work.file("remote") + "/metrics.jsonl"), read_file(dir_->file("local") + "/metrics.jsonl"));
    int images = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir_->file("local") + "/fused")) {
        if (!e.is_regular_file()) continue;
        const std::string relative = fs::relative(e.path(), dir_->file("local")).string();
        EXPECT_EQ(read_file(work.file("remote") + "/" + relative), read_file(e.path().string())) << relative;
        ++images;
    }
    EXPECT_GT(images, 0);
    // B's account of what its capture host sent: every cycle, nothing bad
    // (lost may count A's end, which B's capture thread can see while it
    // waits for a cycle past the last).
    const std::string summary = read_file(work.file("remote") + "/summary.json");
    for (const char* serial : {"SIM-0001", "SIM-0002"})
        EXPECT_NE(summary.find("\"" + std::string(serial) + "\": {\"cycles\": " + std::to_string(kCycles) +
                               ", \"missed\": 0, \"malformed\": 0"),
                  std::string::npos)
            << summary;
}

TEST_F(TwoHostRig, PacketsDroppedNeverMixCyclesAndEveryCycleIsAccountedFor) {
    hosts_->drop_udp('a', 5);
    hosts_->drop_udp('b', 5);
    TempDir work;
    std::string b_err;
    ASSERT_EQ(run_both(work.file("remote"), b_err), 0) << b_err;
    // Each sensor's cycles as the local replay fused them, by their frames.
    std::map<std::string, std::map<std::string, std::string>> local;  // sensor -> frames -> line
    for (const std::string& line : lines_of_file(dir_->file("local") + "/metrics.jsonl"))
        local[field(line, "sensor")][field(line, "frames")] = line;
    std::map<std::string, int> lines;
    for (const std::string& line : lines_of_file(work.file("remote") + "/metrics.jsonl")) {
        const std::string sensor = field(line, "sensor");
        ++lines[sensor];
        if (field(line, "status") != "\"ok\"") {
            // Reported, naming the sensor.
            EXPECT_NE(field(line, "error").find(sensor.substr(1, sensor.size() - 2)), std::string::npos) << line;
            continue;
        }
        // Fused from the frames of one recorded cycle, never two.
        EXPECT_TRUE(local[sensor].count(field(line, "frames"))) << line;
    }
    for (const auto& [sensor, n] : lines) EXPECT_EQ(n, kCycles) << sensor;
    EXPECT_EQ(lines.size(), 2u);
}

// A capture host playing one live simulated DIGIT until killed, started
// again a little later: B says it is gone within a second of the kill, and
// fuses it again once it is back.
TEST_F(TwoHostRig, CaptureHostKilledIsReportedWithinASecondAndTakenBack) {
    TempDir work;
    const std::string domain = std::to_string(own_domain());
    const std::vector<std::string> capture{"run", "--simulate", "--background-frames", "2", "--capture-only",
                                           "--publish", "ros2", "--publish-frames", "--ros-domain", domain};
    const pid_t b = hosts_->start('b', {"run", "--source", "ros2", "--ros-domain", domain, "--duration", "600",
                                        "--skip", "off", "--startup-timeout", "60"},
                                  work.file("b.out"), work.file("b.err"));
    pid_t a = hosts_->start('a', capture, work.file("a.out"), work.file("a.err"));
    auto b_said = [&](const std::string& text, std::size_t from) {
        return read_file(work.file("b.err")).find(text, from) != std::string::npos;
    };
    auto wait_for = [&](const std::string& text, std::size_t from, double seconds) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (!b_said(text, from) && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        return b_said(text, from);
    };
    // B fuses A's cycles: its progress line counts them.
    ASSERT_TRUE(wait_for("1/1 ok", 0, 90)) << read_file(work.file("b.err")) << read_file(work.file("a.err"));
    const std::size_t before = read_file(work.file("b.err")).size();
    kill(a, SIGKILL);
    const auto killed = std::chrono::steady_clock::now();
    wait_exit(a, 10);
    ASSERT_TRUE(wait_for("its capture host is gone", before, 10)) << read_file(work.file("b.err"));
    const double gone_after = std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
    EXPECT_LT(gone_after, 1.0) << "SIM-0001 reported gone " << gone_after << " s after its capture host was killed";
    const std::size_t gone = read_file(work.file("b.err")).size();
    a = hosts_->start('a', capture, work.file("a2.out"), work.file("a2.err"));
    EXPECT_TRUE(wait_for("its capture host is back", gone, 90)) << read_file(work.file("b.err"));
    // The new host numbers its cycles from 0 again: they are its own, not
    // the old host's going backwards.
    EXPECT_FALSE(b_said("going backwards", gone)) << read_file(work.file("b.err"));
    kill(b, SIGTERM);
    EXPECT_EQ(wait_exit(b, 60), 0) << read_file(work.file("b.err"));
    kill(a, SIGTERM);
    wait_exit(a, 30);
}

}  // namespace
}  // namespace vkfuse::test

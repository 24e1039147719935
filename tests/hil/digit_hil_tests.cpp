// The DIGIT tests run inside the HIL virtual machine (tests/hil/run_hil.sh),
// against emulated DIGITs that the kernel's own uvcvideo driver talks to:
// discovery, LED encodings per firmware, every LED setting visible in the
// frames, switch-timing calibration against the emulator's latency, a
// timeout, a corrupt MJPEG frame, and unplug / replug.
//
// tests/hil/in_vm.sh runs the tests for a unit with firmware 2.00, then for
// one with firmware 1.00, and says what it started through the environment:
//   VKFUSE_HIL_SERIAL, VKFUSE_HIL_FIRMWARE   the unit ("D20001", "2.00")
//   VKFUSE_HIL_OTHER            the other unit plugged in beside it
//   VKFUSE_HIL_LATENCY_MS       the LED latency the emulator was given
//   VKFUSE_HIL_CORRUPT_EVERY    it cuts every Nth MJPEG frame short
//   VKFUSE_HIL_UNPLUG, VKFUSE_HIL_REPLUG   shell commands that unplug and replug it
//   VKFUSE_HIL_PAUSE, VKFUSE_HIL_RESUME    shell commands that stop and resume
//                               its stream (the camera goes silent)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/digit_sensor.hpp"
#include "vkfuse/sensor/sim_digit.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse::test {
namespace {

std::string env(const char* name) {
    const char* v = std::getenv(name);
    if (!v || !*v) throw std::runtime_error(std::string(name) + " is not set: run through tests/hil/run_hil.sh");
    return v;
}

void shell(const std::string& command) {
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

std::array<double, 3> mean_rgb(const Frame& f) {
    std::array<double, 3> sum{};
    for (std::size_t i = 0; i < f.pixels.size(); ++i) sum[i % 3] += f.pixels[i];
    const double n = double(f.pixels.size() / 3);
    return {sum[0] / n, sum[1] / n, sum[2] / n};
}

std::unique_ptr<DigitSensor> open(const std::string& serial, DigitEncoding encoding = DigitEncoding::Yuyv,
                                  double timeout_s = 2.0) {
    DigitOptions o;
    o.device = serial;
    o.mode.encoding = encoding;
    o.timeout_s = timeout_s;
    return std::make_unique<DigitSensor>(o);
}

// The mean colour of `count` frames grabbed once the setting has had time
// to show (frames exposed before the request are dropped by the sensor;
// latency_s more skips the frames still switching).
std::array<double, 3> lit_by(DigitSensor& d, const Illumination& setting, double latency_s, int count) {
    d.set_illumination(setting);
    const double shown = d.clock()->now() + latency_s + 0.1;
    Frame f = d.grab();
    while (f.timestamp < shown) f = d.grab();
    std::array<double, 3> mean{};
    for (int i = 0; i < count; ++i, f = d.grab()) {
        const auto m = mean_rgb(f);
        for (int c = 0; c < 3; ++c) mean[c] += m[c] / count;
    }
    std::printf("hil: %s %s: mean rgb %.1f %.1f %.1f over %d frames\n", d.info().serial.c_str(),
                setting.to_string().c_str(), mean[0], mean[1], mean[2], count);
    return mean;
}

double latency_s() { return std::stod(env("VKFUSE_HIL_LATENCY_MS")) / 1000.0; }

TEST(HilDigit, DiscoveryFindsTheUnitItsFirmwareAndModes) {
    const std::vector<DigitDevice> found = find_digits();
    ASSERT_EQ(found.size(), 2u);
    const auto it = std::find_if(found.begin(), found.end(),
                                 [](const DigitDevice& d) { return d.serial == env("VKFUSE_HIL_SERIAL"); });
    ASSERT_NE(it, found.end());
    const DigitDevice& d = *it;
    const DigitDevice& other = found[it == found.begin() ? 1 : 0];
    std::printf("hil: found %s on %s, firmware %s, node %s (and %s on %s)\n", d.serial.c_str(), d.usb_port.c_str(),
                d.firmware.to_string().c_str(), d.video_nodes.empty() ? "-" : d.video_nodes.front().c_str(),
                other.serial.c_str(), other.usb_port.c_str());
    EXPECT_EQ(other.serial, env("VKFUSE_HIL_OTHER"));
    EXPECT_EQ(d.firmware.to_string(), env("VKFUSE_HIL_FIRMWARE"));
    EXPECT_FALSE(d.bootloader);
    ASSERT_EQ(d.video_nodes.size(), 1u) << "the metadata node is left out";
    const std::vector<DigitMode> modes = digit_modes(d.video_nodes.front());
    std::string offered;
    for (const DigitMode& m : modes) offered += m.to_string() + "; ";
    std::printf("hil: modes %s\n", offered.c_str());
    for (const char* m : {"yuyv 320x240@60", "yuyv 320x240@30", "yuyv 640x480@30", "yuyv 640x480@15", "mjpeg 320x240@60",
                          "mjpeg 320x240@30", "mjpeg 640x480@30", "mjpeg 640x480@15"})
        EXPECT_NE(offered.find(std::string(m) + ";"), std::string::npos) << m;
}

TEST(HilDigit, EachLedSettingShowsInTheFrames) {
    auto d = open(env("VKFUSE_HIL_SERIAL"));
    const double lat = latency_s();
    const auto red = lit_by(*d, Illumination({15, 0, 0}), lat, 8);
    const auto green = lit_by(*d, Illumination({0, 15, 0}), lat, 8);
    const auto blue = lit_by(*d, Illumination({0, 0, 15}), lat, 8);
    const auto white = lit_by(*d, Illumination({15, 15, 15}), lat, 8);
    const auto off = lit_by(*d, Illumination({0, 0, 0}), lat, 8);
    EXPECT_GT(red[0], red[1] + 10);
    EXPECT_GT(red[0], red[2] + 10);
    EXPECT_GT(green[1], green[0] + 10);
    EXPECT_GT(green[1], green[2] + 10);
    EXPECT_GT(blue[2], blue[0] + 10);
    EXPECT_GT(blue[2], blue[1] + 10);
    for (int c = 0; c < 3; ++c) EXPECT_GT(white[c], off[c] + 20) << "channel " << c;
    const DigitCounters n = d->counters();
    std::printf("hil: delivered %llu, stale dropped %llu, corrupt %llu\n", (unsigned long long)n.delivered,
                (unsigned long long)n.stale, (unsigned long long)n.corrupt);
    EXPECT_EQ(n.corrupt, 0u);
}

TEST(HilDigit, OldFirmwareTakesOneIntensity) {
    auto d = open(env("VKFUSE_HIL_SERIAL"));
    const double lat = latency_s();
    const auto bright = lit_by(*d, Illumination({15, 15, 15}), lat, 6);
    const auto dim = lit_by(*d, Illumination({5, 5, 5}), lat, 6);
    for (int c = 0; c < 3; ++c) EXPECT_GT(bright[c], dim[c] + 10) << "channel " << c;
    try {
        d->set_illumination(Illumination({0, 15, 0}));
        ADD_FAILURE() << "firmware 1.00 cannot light green alone";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("drives its three LEDs alike"), std::string::npos) << e.what();
    }
}

// uvcvideo stamps a frame when the host's first transfer of it completes (a
// camera that sends no UVC PTS/SCR, as the emulator and, as far as we know,
// the DIGIT). The emulator, like a streaming camera, sends a frame's rows as
// they are read out, so that first transfer leaves one row exposure plus the
// readout of the rows it holds after the frame started: the offset between a
// frame's exposure, which the LED latency is about, and its stamp.
double stamp_offset_s() {
    const SimTiming t = SimDigit(SimDigitOptions{}).timing();  // the emulator's camera, QVGA at 60 fps
    constexpr double kFirstTransferBytes = 32 * 512;  // uvcvideo: 32 packets of the bulk endpoint's 512 bytes
    const double rows = std::ceil((kFirstTransferBytes - 2) / (320 * 2));
    return t.nominal_exposure_s + (rows - 1) * t.row_time_s;
}

TEST(HilDigit, SwitchTimingFindsTheEmulatorsLatency) {
    auto d = open(env("VKFUSE_HIL_SERIAL"));
    const SwitchTiming t = measure_switch_timing(*d, *d->clock());
    const double lat = latency_s(), offset = stamp_offset_s();
    std::printf("hil: switch timing: frame period %.2f ms, latency max %.2f ms = stamp offset %.2f + %.2f "
                "(configured %.2f), clearance %.2f ms, delivery %.2f ms, jitter %.2f ms\n",
                t.frame_period * 1e3, t.latency_max * 1e3, offset * 1e3, (t.latency_max - offset) * 1e3, lat * 1e3,
                t.clearance * 1e3, t.delivery * 1e3, t.jitter * 1e3);
    // What the calibration finds, less the stamp offset, is the configured
    // LED latency to within a frame period (a switch and the host's control
    // request take a few ms through the virtual USB link; 2 ms of slack below
    // for timer granularity).
    EXPECT_GE(t.latency_max - offset, lat - 0.002);
    EXPECT_LE(t.latency_max - offset, lat + t.frame_period);
}

TEST(HilDigit, ASilentCameraTimesOutAndRecovers) {
    auto d = open(env("VKFUSE_HIL_SERIAL"), DigitEncoding::Yuyv, 1.0);
    d->grab();
    shell(env("VKFUSE_HIL_PAUSE"));
    const auto start = std::chrono::steady_clock::now();
    bool timed_out = false;
    try {
        for (int i = 0; i < 100; ++i) d->grab();  // frames already queued, then silence
    } catch (const Error& e) {
        timed_out = e.kind() == ErrorKind::Timeout;
        EXPECT_NE(std::string(e.what()).find("no frame within"), std::string::npos) << e.what();
    }
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    shell(env("VKFUSE_HIL_RESUME"));
    std::printf("hil: silent camera: Timeout after %.2f s\n", waited);
    EXPECT_TRUE(timed_out);
    EXPECT_LT(waited, 3.0);
    d->grab();  // streams again
}

TEST(HilDigit, ACorruptMjpegFrameIsDroppedAndCounted) {
    auto d = open(env("VKFUSE_HIL_SERIAL"), DigitEncoding::Mjpeg);
    const int every = std::stoi(env("VKFUSE_HIL_CORRUPT_EVERY"));
    const int frames = 6 * every;
    for (int i = 0; i < frames; ++i) {
        const Frame f = d->grab();
        ASSERT_EQ(f.pixels.size(), std::size_t(320 * 240 * 3));
    }
    const DigitCounters n = d->counters();
    std::printf("hil: MJPEG: %llu delivered, %llu corrupt dropped (every %d-th sent corrupt)\n",
                (unsigned long long)n.delivered, (unsigned long long)n.corrupt, every);
    // Every `every`-th frame sent is cut short; the sensor saw delivered + corrupt of them.
    const double expected = double(n.delivered + n.corrupt) / every;
    EXPECT_GE(double(n.corrupt), expected - 2) << "corrupt frames delivered as good ones?";
    EXPECT_LE(double(n.corrupt), expected + 2) << "good frames dropped as corrupt?";
}

TEST(HilDigit, UnplugFailsTheSensorWhileTheOtherStreamsAndReplugReopensItBySerial) {
    auto d = open(env("VKFUSE_HIL_SERIAL"), DigitEncoding::Yuyv, 1.0);
    auto other = open(env("VKFUSE_HIL_OTHER"), DigitEncoding::Yuyv, 1.0);
    d->set_illumination(Illumination({0, 15, 0}));
    d->grab();
    other->grab();
    const auto t0 = std::chrono::steady_clock::now();
    const auto since = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    shell(env("VKFUSE_HIL_UNPLUG"));
    std::printf("hil: %.2f s unplugged\n", since());
    // A slow (loaded) host may first let a grab time out (Timeout) before
    // the unplug reaches the driver, and after the replug before the first
    // frame of the reopened stream: waits, not failures. Anything else is.
    const auto transient = [](const Error& e) {
        return e.kind() == ErrorKind::Unplugged || e.kind() == ErrorKind::Timeout;
    };
    bool unplugged = false;
    for (int i = 0; i < 200 && !unplugged; ++i) {
        try {
            d->grab();
        } catch (const Error& e) {
            unplugged = e.kind() == ErrorKind::Unplugged;
            std::printf("hil: %.2f s grab: %s\n", since(), e.what());
            if (!transient(e)) ADD_FAILURE() << e.what();
        }
    }
    ASSERT_TRUE(unplugged);
    // The other unit streams on while this one is gone.
    int others = 0;
    for (; others < 20; ++others) other->grab();
    std::printf("hil: %.2f s %s delivered %d frames meanwhile\n", since(), other->info().serial.c_str(), others);
    shell(env("VKFUSE_HIL_REPLUG"));
    std::printf("hil: %.2f s replugged\n", since());
    Frame back;
    for (int attempt = 0; attempt < 20; ++attempt) {
        try {
            back = d->grab();
            break;
        } catch (const Error& e) {
            std::printf("hil: %.2f s grab: %s\n", since(), e.what());
            ASSERT_TRUE(transient(e)) << e.what();
        }
    }
    std::printf("hil: %.2f s frames again (reopened %llu time)\n", since(),
                (unsigned long long)d->counters().reopened);
    ASSERT_FALSE(back.pixels.empty());
    EXPECT_EQ(d->counters().reopened, 1u);
    EXPECT_EQ(other->counters().reopened, 0u);
    // The setting it had is lit again after the reopen.
    const auto m = lit_by(*d, Illumination({0, 15, 0}), latency_s(), 4);
    EXPECT_GT(m[1], m[0] + 10);
    other->grab();
}

}  // namespace
}  // namespace vkfuse::test

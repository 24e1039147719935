// run_options.hpp - what `vkfuse run` was asked to do, checked before any work.
#pragma once
#include <optional>
#include <string>

#include "args.hpp"
#include "shared_options.hpp"
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/core/skip.hpp"
#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/sensor/digit_sensor.hpp"
#include "vkfuse/rig/rig.hpp"
#include "vkfuse/ros2/publisher.hpp"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::cli {

// How long a cycle waits for a sensor by default. Live sensors: 5 s, then the
// late one is reported. Virtual clocks and replays: a sensor is late only when
// the host is slow (16 simulated DIGITs under AddressSanitizer on 2 cores took
// over 5 s for one cycle), and a timeout there would break the runs'
// determinism, so only a real hang is cut off.
inline constexpr double kLiveTimeoutSeconds = 5.0;
inline constexpr double kSimulatedTimeoutSeconds = 120.0;

// The options that only a simulated DIGIT takes: giving one asks for the simulator.
inline constexpr const char* kSimulatorOptions[] = {"--sensors",      "--motion",      "--motion-period", "--virtual-clock",
                                                    "--camera-auto", "--pressing",    "--simulate"};

struct RunOptions {
    // Real DIGITs (--sensor, by serial or video node); empty: every DIGIT
    // plugged in, unless the simulator was asked for (simulate).
    std::vector<std::string> digits;
    bool simulate = false;  // a simulator option was given
    DigitEncoding encoding = DigitEncoding::Yuyv;
    int sensors = 1;
    std::string object = "coin";
    SimMotion motion = SimMotion::Still;  // simulated DIGITs: how the pressed object moves
    double motion_period_s = 2.0;
    IlluminationSequence sequence;  // the paper's best pair unless --sequence
    FusionSpec fusion;              // wavelet, bior4.4, 3 levels unless told
    Backend backend = Backend::Auto;
    std::optional<int> cycles;
    std::optional<double> duration_s;  // of the sensors' clock
    bool virtual_clock = false;
    bool camera_auto = false;  // simulated DIGITs: auto exposure and white balance on
    std::optional<std::string> replay, record, out;
    bool realtime = false;  // --realtime: a replay at the pace it was recorded
    int background_frames = 0;
    // Skipping: tiles unless --skip says otherwise or there is no
    // background to compare with (--background-frames 0 or 1).
    SkipConfig skip;
    // --metrics: all three unless told; background_diff only with a background.
    MetricSet metrics = MetricSet::all();
    int cycles_in_flight = 1;     // --cycles-in-flight (RigConfig::cycles_in_flight)
    FusionWindow window = FusionWindow::Cycle;  // --window (RigConfig::window), live sensors
    int switch_priority = 10;     // --switch-priority (RigConfig::switch_priority), live sensors on a real clock
    std::optional<int> pressing;  // simulated DIGITs: how many press the object (the first N), default all
    double timeout_s = kLiveTimeoutSeconds;
    // --publish ros2: every cycle on ROS 2's wire too (run_publish.hpp), in
    // domain --ros-domain, else ROS_DOMAIN_ID, else 0.
    bool publish_ros2 = false;
    int ros_domain = 0;
    ros2::ImageEncoding publish_encoding = ros2::ImageEncoding::Rgb8;  // --publish-encoding
    double publish_wait_s = 0;  // --publish-wait: for subscribers before the first cycle
    bool publish_frames = false;  // --publish-frames: each sensor's cycles and background too
    // --capture-only: a capture host: cycles are captured and published or
    // recorded, never fused (no Vulkan device is opened).
    bool capture_only = false;
    // --source ros2: the sensors are a capture host's, heard in ros_domain
    // (the serials: digits, from --sensor; empty: the first host's).
    bool source_ros2 = false;
    double startup_timeout_s = 60;  // --startup-timeout (RigConfig::startup_timeout_s)
    // --serve [ADDR:]PORT: the live page and the Foxglove WebSocket protocol
    // (tools/serve/live_server.hpp), checked while parsing.
    std::optional<std::string> serve;
    int source_queue = 4;           // --queue: cycles each remote sensor keeps (RemoteRigOptions::queue_cycles)
};

inline constexpr const char* kDefaultSequence = "15,15,15+0,15,0";
inline constexpr int kDefaultBackgroundFrames = 20;
inline constexpr int kMaxSimulatedSensors = int(kMaxRigSensors);

// Parses and checks every option (names, ranges, the sequence against the
// DIGIT's LEDs, the object against the simulator's). Throws Error naming the option.
RunOptions parse_run_options(const Args& args);
// What depends on the background (o.background_frames, known by now):
// --skip, --skip-threshold, --cycles-in-flight and --metrics into o.
void background_options(const Args& args, RunOptions& o);

// With --source ros2: the capture hosts' sequence and background count, and
// the sensors' count.
void adopt_remote(RunOptions& options, const Args& args, const IlluminationSequence& sequence, int background_frames,
                  int sensors);

// With --replay: the recorded sequence, fusion and background count wherever
// the command line did not set them, and the recorded object when it named
// none. Throws Error when the dataset cannot serve the run.
void adopt_recording(RunOptions& options, const Args& args, const Dataset& dataset);

}  // namespace vkfuse::cli

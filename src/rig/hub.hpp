// rig/hub.hpp - what the capture threads and the rig share, and the capture
// thread itself.
#pragma once
#include <array>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vkfuse/rig/background.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::rig {

// One sensor's mailbox and state. Written by its capture thread, read by the
// rig, always under Hub::mutex.
inline constexpr std::size_t kMailboxCycles = 3;

struct SensorSlot {
    std::string serial;
    // Complete cycles the rig has not taken yet, oldest first; at most
    // kMailboxCycles, so that a capture thread goes on switching while the
    // rig waits for another sensor or for the CPU (a thread held back past
    // its next switch request loses a frame, and its lateness then holds up
    // every sensor of the cycle).
    std::deque<std::vector<Frame>> ready;
    std::optional<SwitchTiming> timing;
    std::string switch_scheduling;  // Switcher::set_switch_priority's answer
    std::uint64_t windows_held = 0;  // Switcher::windows_held, as of the last delivery
    bool background_done = false;
    bool background_applied = false;  // rig side: handed to the fusion engine
    std::vector<Image> background;    // per slot of the sequence
    std::vector<Image> deviation;     // per slot: the background frames' per-pixel standard deviation
    // Watch cycles (RigConfig::watch_when_idle): the rig's verdict on each
    // cycle it took from this sensor (by delivery, from 0): idle with no
    // changed tile, or not. The last few only; judged counts them all.
    std::uint64_t judged = 0;
    std::array<bool, 4> idle_verdicts{};
    bool idle_verdict(std::uint64_t delivery) const { return idle_verdicts[delivery % 4]; }
    // A background applied after cycles began: verdicts before it do not count.
    std::uint64_t verdicts_from = 0;
    bool failed = false;
    // Gone for now (Failed: unplugged; Timeout: silent): not waited for,
    // reported with `error` until it delivers again.
    std::optional<SensorStatus> lost;
    std::string error;
    bool exited = false;
};

// Owned through shared_ptr by the rig and every capture thread, so a thread
// left behind in a stuck sensor call never outlives what it touches.
struct Hub {
    std::mutex mutex;
    std::condition_variable changed;
    std::vector<SensorSlot> slots;  // sized before the threads start, never resized
    bool stop = false;

    // Work that touches objects the Rig or its caller own (the Vulkan context
    // through the background model, the caller's callbacks) runs under
    // work_mutex and only while !stop: ~Rig sets stop, then takes work_mutex
    // once, and after that no thread touches them again.
    std::mutex work_mutex;
    Context* context = nullptr;              // null: CPU background means
    std::unique_ptr<BackgroundModel> model;  // built on first use

    // The mean of frames; call with work_mutex held.
    Image average(std::span<const FrameView> frames);
};

struct CaptureJob {
    std::size_t index = 0;
    RigSensor sensor;
    std::shared_ptr<const RigConfig> config;
    std::shared_ptr<Hub> hub;
};

// The body of one sensor's capture thread: calibrate, background, then cycles
// into the mailbox until the hub stops. Never throws: a failure is recorded
// in the slot with the serial.
void capture_main(CaptureJob job);

// message prefixed with "<serial>: " unless it already names the serial first.
std::string with_serial(const std::string& serial, const std::string& message);

}  // namespace vkfuse::rig

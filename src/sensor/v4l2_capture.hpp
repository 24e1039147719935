// v4l2_capture.hpp - one V4L2 video capture node, streaming through mmap'ed
// buffers: the part of a DIGIT that is an ordinary UVC camera.
//
// Every call that can block waits at most the timeout it is given (poll), so
// a camera that stops sending is a Timeout, never a hang; a camera that is
// unplugged (ENODEV, POLLERR) is an Unplugged error naming the subject.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace vkfuse::v4l2 {

// A control's range as VIDIOC_QUERYCTRL reports it.
struct ControlInfo {
    std::int32_t minimum = 0;
    std::int32_t maximum = 0;
    std::int32_t step = 1;
    std::int32_t default_value = 0;
    std::uint32_t type = 0;  // V4L2_CTRL_TYPE_*
};

// One frame size and rate a node offers for a pixel format.
struct Mode {
    std::uint32_t fourcc = 0;
    int width = 0;
    int height = 0;
    double fps = 0;
};

// A filled buffer, lent to the caller until requeue().
struct Filled {
    int index = 0;
    std::span<const std::uint8_t> bytes;
    double timestamp = 0;       // seconds on CLOCK_MONOTONIC
    bool driver_timestamp = false;  // false: the driver gave none, stamped at dequeue
    bool error = false;         // the driver flagged the data as damaged
    std::uint32_t sequence = 0;
};

// "YUYV" for a fourcc.
std::string fourcc_text(std::uint32_t fourcc);

// Seconds on CLOCK_MONOTONIC, the clock V4L2 drivers stamp buffers with.
double monotonic_now();

class Capture {
public:
    // Opens `node` for capture; `subject` (a serial, or the node) starts
    // every error message. Throws Error(Device) for a node that cannot be
    // opened, is busy, or is not a streaming video capture node.
    Capture(const std::string& node, std::string subject);
    ~Capture();
    Capture(const Capture&) = delete;
    Capture& operator=(const Capture&) = delete;

    // Every size and rate the node offers (discrete ones; stepwise sizes are
    // left out).
    std::vector<Mode> modes() const;
    // Sets the format and frame rate; throws Error(Device) when the driver
    // picks anything else.
    void configure(const Mode& mode);
    // Maps `buffers` buffers, queues them all and starts streaming.
    void start(int buffers);
    // The next filled buffer, or nullopt when none came within timeout_s.
    std::optional<Filled> dequeue(double timeout_s);
    void requeue(int index);

    std::optional<ControlInfo> query_control(std::uint32_t id) const;
    void set_control(std::uint32_t id, std::int32_t value);
    std::int32_t get_control(std::uint32_t id) const;

private:
    [[noreturn]] void fail(const std::string& what, int err) const;
    void stop() noexcept;

    struct Mapping {
        void* data = nullptr;
        std::size_t length = 0;
    };
    int fd_ = -1;
    std::string subject_;
    std::vector<Mapping> mappings_;
    bool streaming_ = false;
};

}  // namespace vkfuse::v4l2

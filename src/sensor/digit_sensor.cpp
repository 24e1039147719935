// A real DIGIT (vkfuse/sensor/digit_sensor.hpp): sysfs finds it by serial,
// V4L2 streams it (v4l2_capture.hpp), frame_codec.hpp turns its frames into
// RGB, and the zoom control lights its LEDs.
#include "vkfuse/sensor/digit_sensor.hpp"

#include <linux/videodev2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "frame_codec.hpp"
#include "v4l2_capture.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

constexpr std::uint32_t fourcc(DigitEncoding e) {
    return e == DigitEncoding::Mjpeg ? V4L2_PIX_FMT_MJPEG : V4L2_PIX_FMT_YUYV;
}

// The camera controls a rig needs fixed, and the value that fixes each.
struct Lock {
    std::uint32_t id;
    std::int32_t value;
    const char* name;
};
constexpr Lock kCameraLocks[] = {
    {V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_MANUAL, "auto exposure"},
    {V4L2_CID_AUTO_WHITE_BALANCE, 0, "auto white balance"},
};

// How often a gone DIGIT is looked for while grab() waits for it.
constexpr double kReplugPollS = 0.05;

bool is_node(const std::string& device) { return !device.empty() && device.front() == '/'; }

// The DIGIT options.device names, and the capture node to open.
std::pair<DigitDevice, std::string> locate(const DigitOptions& o) {
    const std::vector<DigitDevice> digits = find_digits(o.where);
    std::string serials;
    for (const DigitDevice& d : digits) {
        if (d.bootloader) continue;
        serials += (serials.empty() ? "" : ", ") + d.serial;
        if (is_node(o.device)) {
            if (std::find(d.video_nodes.begin(), d.video_nodes.end(), o.device) != d.video_nodes.end())
                return {d, o.device};
        } else if (d.serial == o.device) {
            if (d.video_nodes.empty())
                throw Error(ErrorKind::Unplugged, o.device + ": plugged in but has no video capture node yet");
            return {d, d.video_nodes.front()};
        }
    }
    const bool booting = std::any_of(digits.begin(), digits.end(), [](const DigitDevice& d) { return d.bootloader; });
    std::string message = o.device + (is_node(o.device) ? ": not the capture node of a DIGIT (USB 2833:0209)"
                                                         : ": no DIGIT with this serial is plugged in");
    message += serials.empty() ? " (none found" : " (found " + serials;
    message += booting ? "; one is in its bootloader)" : ")";
    throw Error(ErrorKind::InvalidArgument, message);
}

}  // namespace

std::string_view to_string(DigitEncoding e) { return e == DigitEncoding::Mjpeg ? "mjpeg" : "yuyv"; }

DigitEncoding parse_digit_encoding(std::string_view name, std::string_view what) {
    for (DigitEncoding e : {DigitEncoding::Yuyv, DigitEncoding::Mjpeg})
        if (name == to_string(e)) return e;
    throw Error(ErrorKind::InvalidArgument,
                std::string(what) + ": unknown encoding '" + std::string(name) + "' (yuyv or mjpeg)");
}

std::string DigitMode::to_string() const {
    char text[64];
    std::snprintf(text, sizeof text, "%s %dx%d@%g", std::string(vkfuse::to_string(encoding)).c_str(), width, height,
                  fps);
    return text;
}

struct DigitSensor::Impl {
    DigitOptions options;
    DigitDevice device;
    std::string serial;  // what errors name; fixed once opened
    std::unique_ptr<v4l2::Capture> capture;
    v4l2::ControlInfo led;
    Illumination setting{{15, 15, 15}};
    double stale_before = 0;  // frames stamped earlier were exposed before the last LED request
    DigitCounters counters;

    void open(const std::string& node) {
        auto c = std::make_unique<v4l2::Capture>(node, serial);
        c->configure({fourcc(options.mode.encoding), options.mode.width, options.mode.height, options.mode.fps});
        const auto zoom = c->query_control(kDigitLedControl);
        if (!zoom)
            throw Error(ErrorKind::Device, serial + ": has no LED control (V4L2 zoom_absolute): not a DIGIT's firmware");
        led = *zoom;
        for (const Lock& lock : kCameraLocks)
            if (c->query_control(lock.id)) {
                try {
                    c->set_control(lock.id, lock.value);
                } catch (const Error& e) {
                    if (e.kind() == ErrorKind::Unplugged) throw;
                    throw Error(ErrorKind::Device, serial + ": cannot turn off " + lock.name + ": " + e.what());
                }
            }
        c->set_control(kDigitLedControl, digit_led_value(setting, device.firmware, {led.minimum, led.maximum}));
        c->start(options.buffers);
        stale_before = v4l2::monotonic_now();
        capture = std::move(c);
    }

    // Opens the DIGIT again after an unplug, waiting up to `deadline` for its serial.
    void reopen(double deadline) {
        DigitOptions by_serial = options;
        by_serial.device = serial;
        for (;;) {
            try {
                auto [found, node] = locate(by_serial);
                device = found;
                open(node);
                ++counters.reopened;
                return;
            } catch (const Error& e) {
                if (e.kind() != ErrorKind::Unplugged && e.kind() != ErrorKind::InvalidArgument) throw;
            }
            if (v4l2::monotonic_now() >= deadline)
                throw Error(ErrorKind::Unplugged, serial + ": unplugged; not back within " +
                                                      std::to_string(options.timeout_s) + " s");
            std::this_thread::sleep_for(std::chrono::duration<double>(kReplugPollS));
        }
    }

    // Runs an operation on the open camera; an unplug closes it.
    template <class F>
    auto guarded(F&& f) {
        try {
            return f(*capture);
        } catch (const Error& e) {
            if (e.kind() == ErrorKind::Unplugged) capture.reset();
            throw;
        }
    }

    bool decode(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& rgb) const {
        const DigitMode& m = options.mode;
        if (m.encoding == DigitEncoding::Yuyv) return yuyv_to_rgb(bytes, m.width, m.height, rgb);
        std::string why;
        return mjpeg_to_rgb(bytes, m.width, m.height, rgb, why);
    }
};

DigitSensor::DigitSensor(const DigitOptions& options) : impl_(std::make_unique<Impl>()) {
    Impl& im = *impl_;
    im.options = options;
    if (options.device.empty()) throw Error(ErrorKind::InvalidArgument, "DIGIT: no serial or video node given");
    if (!(options.timeout_s > 0)) throw Error(ErrorKind::InvalidArgument, options.device + ": timeout must be > 0");
    if (options.buffers < 2 || options.buffers > 32)
        throw Error(ErrorKind::InvalidArgument, options.device + ": buffers must be 2..32");
    auto [found, node] = locate(options);
    im.device = found;
    im.serial = found.serial.empty() ? options.device : found.serial;
    im.open(node);
}

DigitSensor::~DigitSensor() = default;

SensorInfo DigitSensor::info() const {
    const DigitMode& m = impl_->options.mode;
    return {"DIGIT", impl_->serial, m.width, m.height, m.fps, LedLayout::digit()};
}

void DigitSensor::set_illumination(const Illumination& setting) {
    Impl& im = *impl_;
    const std::int32_t value = digit_led_value(setting, im.device.firmware, {im.led.minimum, im.led.maximum});
    im.setting = setting;
    if (!im.capture) return;  // unplugged: applied when it is reopened
    im.guarded([&](v4l2::Capture& c) { c.set_control(kDigitLedControl, value); });
    im.stale_before = v4l2::monotonic_now();
}

Frame DigitSensor::grab() {
    Impl& im = *impl_;
    const double deadline = v4l2::monotonic_now() + im.options.timeout_s;
    if (!im.capture) im.reopen(deadline);
    for (;;) {
        const double left = deadline - v4l2::monotonic_now();
        const auto filled = im.guarded([&](v4l2::Capture& c) { return c.dequeue(std::max(left, 0.0)); });
        if (!filled)
            throw Error(ErrorKind::Timeout,
                        im.serial + ": no frame within " + std::to_string(im.options.timeout_s) + " s");
        Frame f;
        bool usable = false;
        if (filled->timestamp < im.stale_before)
            ++im.counters.stale;
        else if (filled->error || filled->bytes.empty() || !im.decode(filled->bytes, f.pixels))
            ++im.counters.corrupt;
        else
            usable = true;
        im.guarded([&](v4l2::Capture& c) { c.requeue(filled->index); });
        if (!usable) continue;
        f.index = im.counters.delivered++;
        f.timestamp = filled->timestamp;
        f.height = im.options.mode.height;
        f.width = im.options.mode.width;
        return f;
    }
}

std::shared_ptr<Clock> DigitSensor::clock() const { return make_monotonic_clock(); }
DigitDevice DigitSensor::device() const { return impl_->device; }
DigitCounters DigitSensor::counters() const { return impl_->counters; }

std::vector<DigitMode> digit_modes(const std::string& node) {
    std::vector<DigitMode> out;
    try {
        const v4l2::Capture capture(node, node);
        for (const v4l2::Mode& m : capture.modes())
            for (DigitEncoding e : {DigitEncoding::Yuyv, DigitEncoding::Mjpeg})
                if (m.fourcc == fourcc(e)) out.push_back({m.width, m.height, m.fps, e});
    } catch (const Error&) {
    }
    return out;
}

}  // namespace vkfuse

// vkfuse/sensor/digit_sensor.hpp - a real DIGIT as a Sensor: V4L2 streaming,
// LED control across firmware versions, and coming back after an unplug.
//
// Frames are delivered as the DIGIT's image sensor streams them: landscape,
// 320 wide x 240 high at QVGA (as SimDigit renders them). digit-interface's
// get_frame() instead transposes and flips them to portrait:
// portrait(i, j) = landscape(j, width - 1 - i).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/sensor/digit.hpp"
#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse {

enum class DigitEncoding {
    Yuyv,   // uncompressed 4:2:2: no compression artefacts in what is fused
    Mjpeg,  // Motion-JPEG, decoded with libjpeg-turbo
};
std::string_view to_string(DigitEncoding encoding);  // "yuyv", "mjpeg"
// Throws Error(InvalidArgument) "<what>: unknown encoding ...".
DigitEncoding parse_digit_encoding(std::string_view name, std::string_view what = "--encoding");

// A size and rate a DIGIT streams: 320x240 at 60 or 30 fps, 640x480 at 30 or 15.
struct DigitMode {
    int width = 320;
    int height = 240;
    double fps = 60;
    DigitEncoding encoding = DigitEncoding::Yuyv;
    std::string to_string() const;  // "yuyv 320x240@60"
};

struct DigitOptions {
    // Which DIGIT: its serial ("D20001") or one of its video nodes ("/dev/video0").
    std::string device;
    DigitMode mode;
    double timeout_s = 1.0;  // grab() throws Error(Timeout) after this long without a frame
    int buffers = 4;         // V4L2 buffers queued to the driver
    DigitDiscovery where;    // where sysfs and /dev are
};

// What the sensor dropped and why, since it was opened.
struct DigitCounters {
    std::uint64_t delivered = 0;
    std::uint64_t stale = 0;    // exposed before the last LED request (by timestamp)
    std::uint64_t corrupt = 0;  // flagged by the driver, or not decodable
    std::uint64_t reopened = 0; // times it came back after an unplug
};

class DigitSensor : public Sensor {
public:
    // Opens the DIGIT, sets the mode, locks auto exposure and auto white
    // balance where the camera has those controls (the rig compares LED
    // settings; an automatic camera would even them out), lights (15,15,15)
    // and starts streaming. Throws Error naming the device:
    //   InvalidArgument: no DIGIT by that serial or node is plugged in, it is
    //                    in its bootloader, or the node is not a DIGIT's;
    //   Device:          the camera refuses the mode, has no LED control, or
    //                    cannot be opened (busy, permissions).
    explicit DigitSensor(const DigitOptions& options);
    ~DigitSensor() override;

    SensorInfo info() const override;  // model "DIGIT", its serial and mode, LedLayout::digit()
    // Sends the setting now (digit_led_value for this firmware). Frames whose
    // timestamps precede the request are dropped by grab(): they were exposed
    // before it. Throws Error(InvalidArgument) for a setting the firmware
    // cannot show, Error(Unplugged) when the DIGIT is gone.
    void set_illumination(const Illumination& setting) override;
    // The next frame, RGB, with the driver's timestamp on clock(). Frames the
    // driver flags or that do not decode are dropped and counted.
    //   Error(Timeout):   no frame within options.timeout_s;
    //   Error(Unplugged): the DIGIT went away. Later calls look for its serial
    //                     again (for up to timeout_s each) and, once it is
    //                     back, reopen it with the same mode and LED setting.
    Frame grab() override;

    // CLOCK_MONOTONIC, the clock frame timestamps are on (for a Rig).
    std::shared_ptr<Clock> clock() const;
    DigitDevice device() const;  // as found when (re)opened
    DigitCounters counters() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

// The modes a DIGIT's capture node offers (VIDIOC_ENUM_FMT and friends),
// for `vkfuse devices`; empty when the node cannot be opened.
std::vector<DigitMode> digit_modes(const std::string& node);

}  // namespace vkfuse

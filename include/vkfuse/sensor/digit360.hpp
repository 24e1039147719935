// vkfuse/sensor/digit360.hpp - the Digit 360's LEDs: eight RGB LEDs driven by
// protobuf messages over the sensor's CDC-ACM serial port (its camera is a
// separate UVC device, USB 2833:b015).
//
// The message is digit360.Digit360Message { lighting_control (7):
// LightingControl { alpha (1, float), channel (2, LightingChannel: 1..8 one
// LED, 9 all), r (3), g (4), b (5) } } from the public digit360_proto_v1.proto,
// encoded here by hand (proto3: fields at their default are left out).
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "vkfuse/sensor/digit.hpp"
#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse {

inline constexpr UsbId kDigit360CameraUsb{0x2833, 0xb015};

// How messages are delimited on the wire.
enum class Digit360Framing {
    // COBS-encoded, each followed by a 0x00 byte: how the sensor frames what
    // it sends, so a reader can always find the next message.
    Cobs,
    // The bare message, one per write(), as the public digit360 Python
    // interface sends its LightingControl messages.
    Raw,
};

// One LightingControl message per LED (LightingChannel 1..8) for a 24-channel
// setting of LedLayout::digit360() (led<i>.r, .g, .b at channels 3i..3i+2), or
// one message for all (LightingChannel 9) when the eight LEDs are alike.
// Throws Error(InvalidArgument) for a setting that does not fit the layout.
std::vector<std::vector<std::uint8_t>> digit360_lighting_messages(const Illumination& setting, float alpha);

// Consistent Overhead Byte Stuffing: `data` without any 0x00 byte, plus the
// 0x00 delimiter. cobs_decode takes a frame without its delimiter and
// returns false for a malformed one.
std::vector<std::uint8_t> cobs_encode(std::span<const std::uint8_t> data);
bool cobs_decode(std::span<const std::uint8_t> frame, std::vector<std::uint8_t>& data);

struct Digit360LedOptions {
    std::string tty;                 // the sensor's data port, "/dev/ttyACM0"
    Digit360Framing framing = Digit360Framing::Cobs;
    float alpha = 255.0f;            // LightingControl.alpha, as the digit360 ROS node sends by default
    double write_timeout_s = 0.5;    // a port that takes nothing this long is an error, never a hang
};

// The LEDs of one Digit 360. Errors name the port.
class Digit360Leds {
public:
    // Opens the port raw (no echo, no line discipline, 8N1). Throws
    // Error(Device) when it cannot be opened or is not a terminal.
    explicit Digit360Leds(const Digit360LedOptions& options);
    ~Digit360Leds();
    Digit360Leds(const Digit360Leds&) = delete;
    Digit360Leds& operator=(const Digit360Leds&) = delete;

    LedLayout layout() const { return LedLayout::digit360(); }
    // Sends the setting (digit360_lighting_messages). Throws
    // Error(InvalidArgument) for a setting that does not fit, Error(Timeout)
    // when the port takes nothing for write_timeout_s, Error(Unplugged) when
    // the port went away.
    void set(const Illumination& setting);

private:
    void write_all(std::span<const std::uint8_t> bytes);

    Digit360LedOptions options_;
    int fd_ = -1;
};

}  // namespace vkfuse

// vkfuse/sensor/digit.hpp - the DIGIT's USB identity, how its LEDs are driven,
// and finding the DIGITs plugged into this machine.
//
// A DIGIT is a UVC camera: USB 2833:0209, product "DIGIT", its serial
// ("D20001") in the serial string descriptor and its firmware revision in
// bcdDevice (0x0200 = 2.00). Its LEDs are driven through the V4L2 zoom
// control. A DIGIT in its bootloader (DFU) enumerates as 0403:0fde: it is
// reported, never opened.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse {

struct UsbId {
    std::uint16_t vendor = 0;
    std::uint16_t product = 0;
    friend bool operator==(const UsbId&, const UsbId&) = default;
};
inline constexpr UsbId kDigitUsb{0x2833, 0x0209};
inline constexpr UsbId kDigitBootloaderUsb{0x0403, 0x0fde};
// V4L2_CID_ZOOM_ABSOLUTE: the control a DIGIT's firmware reads its LEDs from.
inline constexpr std::uint32_t kDigitLedControl = 0x009a090d;

struct DigitFirmware {
    int major = 0;
    int minor = 0;
    // bcdDevice as sysfs gives it, four hex digits ("0200" -> 2.00);
    // nullopt for anything else.
    static std::optional<DigitFirmware> from_bcd(std::string_view text);
    std::string to_string() const;  // "2.00"
    // Firmware 2.00 and later take one 4-bit level per LED; older firmware
    // one intensity for all three.
    bool per_led_levels() const { return major >= 2; }
};

// The range the device reports for the LED control (VIDIOC_QUERYCTRL).
struct ControlRange {
    std::int32_t minimum = 0;
    std::int32_t maximum = 0;
};

// The LED control's value that lights `setting` (r, g, b, each 0..15):
//   firmware >= 2.00: (r << 8) | (g << 4) | b;
//   older firmware:   one intensity round(level x maximum / 15) for a setting
//                     whose three levels are equal.
// Throws Error(InvalidArgument) naming the setting and the firmware when the
// firmware cannot show it (unequal levels on old firmware) or the value falls
// outside the device's range (e.g. LEDs off where the minimum is 1).
std::int32_t digit_led_value(const Illumination& setting, DigitFirmware firmware, ControlRange range);
// What the firmware lights for a control value (digit_led_value's inverse, as
// a DIGIT reads the control): per LED from bits 8-11, 4-7 and 0-3, or one
// level round(value x 15 / maximum) for all three on older firmware.
Illumination digit_led_setting(std::int32_t value, DigitFirmware firmware, ControlRange range);

// One DIGIT found on the USB bus.
struct DigitDevice {
    std::string serial;     // "" for one in its bootloader, which has none
    std::string usb_port;   // its sysfs name, "1-1.2": where it is plugged
    DigitFirmware firmware;
    bool bootloader = false;  // in DFU: not a camera, flash it first
    // Its video capture nodes ("/dev/video0"), sorted; metadata nodes, which
    // a UVC camera has too, are left out.
    std::vector<std::string> video_nodes;
};

struct DigitDiscovery {
    std::string sysfs = "/sys";  // where bus/usb/devices and class/video4linux are
    std::string dev = "/dev";    // where the video nodes are opened
    // Whether a node captures video (V4L2_CAP_VIDEO_CAPTURE); null: ask the
    // device (VIDIOC_QUERYCAP), or where it cannot be opened, take the
    // interface's first node (sysfs `index` 0) as the capture node.
    std::function<bool(const std::string& node)> is_capture;
};

// Every DIGIT plugged in (bootloaders included), sorted by serial then port.
// A machine without USB or video devices has none: an empty list, no error.
std::vector<DigitDevice> find_digits(const DigitDiscovery& where = {});

}  // namespace vkfuse

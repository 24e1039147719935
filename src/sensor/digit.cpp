// The DIGIT's firmware revisions, LED control values and discovery through
// sysfs (vkfuse/sensor/digit.hpp). libusb alone cannot say which /dev/videoN
// belongs to which USB device; sysfs links each video node to its USB
// interface, whose parent is the device.
#include "vkfuse/sensor/digit.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

namespace fs = std::filesystem;

// A sysfs attribute's first line, trailing white space removed.
std::optional<std::string> attribute(const fs::path& path) {
    std::ifstream in(path);
    std::string line;
    if (!in || !std::getline(in, line)) return std::nullopt;
    while (!line.empty() && (line.back() == ' ' || line.back() == '\n' || line.back() == '\r')) line.pop_back();
    return line;
}

std::optional<std::uint16_t> hex16(const std::optional<std::string>& text) {
    if (!text || text->size() != 4) return std::nullopt;
    std::uint16_t v = 0;
    for (char c : *text) {
        const int digit = c >= '0' && c <= '9' ? c - '0'
                          : c >= 'a' && c <= 'f' ? c - 'a' + 10
                          : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                 : -1;
        if (digit < 0) return std::nullopt;
        v = std::uint16_t(v * 16 + digit);
    }
    return v;
}

std::optional<UsbId> usb_id(const fs::path& device) {
    const auto vendor = hex16(attribute(device / "idVendor")), product = hex16(attribute(device / "idProduct"));
    if (!vendor || !product) return std::nullopt;
    return UsbId{*vendor, *product};
}

// V4L2_CAP_VIDEO_CAPTURE from the node itself, else the interface's first node.
bool capture_node(const std::string& node, const fs::path& sysfs_entry) {
    const int fd = ::open(node.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd >= 0) {
        v4l2_capability cap{};
        const bool queried = ::ioctl(fd, VIDIOC_QUERYCAP, &cap) == 0;
        ::close(fd);
        if (queried) {
            const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
            return (caps & V4L2_CAP_VIDEO_CAPTURE) != 0;
        }
    }
    return attribute(sysfs_entry / "index") == std::optional<std::string>("0");
}

// The video nodes whose USB interface belongs to `device` (a canonical path).
std::vector<std::string> video_nodes(const fs::path& device, const DigitDiscovery& where) {
    std::vector<std::string> nodes;
    std::error_code ec;
    for (const fs::directory_entry& v : fs::directory_iterator(fs::path(where.sysfs) / "class/video4linux", ec)) {
        std::error_code link;
        const fs::path interface = fs::canonical(v.path() / "device", link);
        if (link || interface.parent_path() != device) continue;
        const std::string node = (fs::path(where.dev) / v.path().filename()).string();
        if (where.is_capture ? where.is_capture(node) : capture_node(node, v.path())) nodes.push_back(node);
    }
    std::sort(nodes.begin(), nodes.end());
    return nodes;
}

}  // namespace

std::optional<DigitFirmware> DigitFirmware::from_bcd(std::string_view text) {
    const std::optional<std::uint16_t> bcd = hex16(std::string(text));
    if (!bcd) return std::nullopt;
    const auto bcd_pair = [](unsigned byte) { return int((byte >> 4) * 10 + (byte & 0xf)); };
    for (unsigned shift : {0u, 4u, 8u, 12u})
        if (((*bcd >> shift) & 0xf) > 9) return std::nullopt;
    return DigitFirmware{bcd_pair(*bcd >> 8), bcd_pair(*bcd & 0xff)};
}

std::string DigitFirmware::to_string() const {
    char text[16];
    std::snprintf(text, sizeof text, "%d.%02d", major, minor);
    return text;
}

std::int32_t digit_led_value(const Illumination& setting, DigitFirmware firmware, ControlRange range) {
    setting.check(LedLayout::digit());
    const int r = setting.level(0), g = setting.level(1), b = setting.level(2);
    const std::string subject = "illumination " + setting.to_string() + ": DIGIT firmware " + firmware.to_string();
    std::int32_t value = 0;
    if (firmware.per_led_levels()) {
        value = (r << 8) | (g << 4) | b;
    } else {
        if (r != g || g != b)
            throw Error(ErrorKind::InvalidArgument, subject + " drives its three LEDs alike: the levels must be equal");
        value = std::int32_t(std::lround(double(r) * double(range.maximum) / 15.0));
    }
    if (value < range.minimum || value > range.maximum)
        throw Error(ErrorKind::InvalidArgument, subject + " takes LED values " + std::to_string(range.minimum) + ".." +
                                                    std::to_string(range.maximum) + ", not " + std::to_string(value));
    return value;
}

Illumination digit_led_setting(std::int32_t value, DigitFirmware firmware, ControlRange range) {
    const std::int32_t v = std::clamp(value, range.minimum, range.maximum);
    if (firmware.per_led_levels()) return Illumination({(v >> 8) & 15, (v >> 4) & 15, v & 15});
    const int level = range.maximum > 0 ? int(std::lround(double(v) * 15.0 / double(range.maximum))) : 0;
    return Illumination({level, level, level});
}

std::vector<DigitDevice> find_digits(const DigitDiscovery& where) {
    std::vector<DigitDevice> found;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::path(where.sysfs) / "bus/usb/devices", ec)) {
        const std::string name = e.path().filename().string();
        if (name.find(':') != std::string::npos) continue;  // an interface, not a device
        const std::optional<UsbId> id = usb_id(e.path());
        if (!id || (*id != kDigitUsb && *id != kDigitBootloaderUsb)) continue;
        DigitDevice d;
        d.usb_port = name;
        d.bootloader = *id == kDigitBootloaderUsb;
        d.serial = d.bootloader ? "" : attribute(e.path() / "serial").value_or("");
        if (const auto bcd = attribute(e.path() / "bcdDevice"))
            d.firmware = DigitFirmware::from_bcd(*bcd).value_or(DigitFirmware{});
        std::error_code link;
        const fs::path device = fs::canonical(e.path(), link);
        if (!d.bootloader && !link) d.video_nodes = video_nodes(device, where);
        found.push_back(std::move(d));
    }
    std::sort(found.begin(), found.end(), [](const DigitDevice& a, const DigitDevice& b) {
        return a.serial != b.serial ? a.serial < b.serial : a.usb_port < b.usb_port;
    });
    return found;
}

}  // namespace vkfuse

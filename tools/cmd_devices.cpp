// vkfuse devices: the DIGITs plugged into this machine.
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "standard_output.hpp"
#include "vkfuse/sensor/digit.hpp"
#include "vkfuse/sensor/digit_sensor.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--sysfs", "", "DIR", "read this sysfs tree instead of /sys (a captured or emulated machine's)"},
};

constexpr CommandSpec kSpec{
    "devices",
    "list the DIGITs plugged into this machine",
    "vkfuse devices [--sysfs DIR]",
    "Prints one line per DIGIT found on the USB bus, one JSON object each:\n"
    "  {\"serial\": S, \"usb\": PORT, \"firmware\": \"2.00\", \"bootloader\": false,\n"
    "   \"video_nodes\": [\"/dev/video0\"], \"modes\": [\"yuyv 320x240@60\", ...]}\n"
    "(modes: what its first node streams; empty when it cannot be opened).\n"
    "A DIGIT in its bootloader (USB 0403:0fde) is listed with \"bootloader\": true\n"
    "and no nodes: it is not a camera until its firmware is flashed. With no DIGIT\n"
    "plugged in it says so on stderr and exits 0.",
    kOptions,
    "vkfuse devices",
};

std::string device_line(const DigitDevice& d) {
    std::string nodes;
    for (const std::string& n : d.video_nodes) nodes += (nodes.empty() ? "" : ", ") + json_string(n);
    std::string modes;
    if (!d.video_nodes.empty())
        for (const DigitMode& m : digit_modes(d.video_nodes.front()))
            modes += (modes.empty() ? "" : ", ") + json_string(m.to_string());
    return "{\"serial\": " + json_string(d.serial) + ", \"usb\": " + json_string(d.usb_port) +
           ", \"firmware\": " + json_string(d.firmware.to_string()) +
           ", \"bootloader\": " + (d.bootloader ? "true" : "false") + ", \"video_nodes\": [" + nodes + "], \"modes\": [" + modes + "]}";
}

int run(const Args& args) {
    if (!args.operands().empty()) args.usage_error("unexpected operand " + args.operands().front());
    DigitDiscovery where;
    if (auto v = args.value("--sysfs")) where.sysfs = *v;
    const std::vector<DigitDevice> found = find_digits(where);
    if (found.empty()) {
        std::fprintf(stderr, "vkfuse devices: no DIGIT found (USB %04x:%04x under %s/bus/usb/devices)\n",
                     kDigitUsb.vendor, kDigitUsb.product, where.sysfs.c_str());
        return 0;
    }
    for (const DigitDevice& d : found) std::printf("%s\n", device_line(d).c_str());
    return 0;
}

}  // namespace

const Command devices_command{kSpec, run};

}  // namespace vkfuse::cli

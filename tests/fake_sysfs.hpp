// fake_sysfs.hpp - a sysfs tree laid out as Linux lays out USB cameras, for
// testing discovery without the devices: devices/ holds the real directories,
// bus/usb/devices/ and class/video4linux/ link into it, and each video node's
// `device` links to its USB interface.
#pragma once
#include <filesystem>
#include <fstream>
#include <string>

namespace vkfuse::test {

class FakeSysfs {
public:
    explicit FakeSysfs(std::filesystem::path root) : root_(std::move(root)) {
        std::filesystem::create_directories(root_ / "bus/usb/devices");
        std::filesystem::create_directories(root_ / "class/video4linux");
    }

    // A USB device at `port` ("1-1"); serial and bcd are left out when empty.
    void add_usb(const std::string& port, const std::string& vendor, const std::string& product,
                 const std::string& serial, const std::string& bcd) {
        const std::filesystem::path dir = device_dir(port);
        std::filesystem::create_directories(dir);
        write(dir / "idVendor", vendor);
        write(dir / "idProduct", product);
        if (!serial.empty()) write(dir / "serial", serial);
        if (!bcd.empty()) write(dir / "bcdDevice", bcd);
        std::filesystem::create_directory_symlink(dir, root_ / "bus/usb/devices" / port);
        const std::string interface = port + ":1.0";
        std::filesystem::create_directories(dir / interface);
        std::filesystem::create_directory_symlink(dir / interface, root_ / "bus/usb/devices" / interface);
    }

    // videoN on the first interface of the device at `port`, sysfs index `index`.
    void add_video(const std::string& port, const std::string& name, int index) {
        const std::filesystem::path node = device_dir(port) / (port + ":1.0") / "video4linux" / name;
        std::filesystem::create_directories(node);
        write(node / "index", std::to_string(index));
        std::filesystem::create_directory_symlink("../..", node / "device");
        std::filesystem::create_directory_symlink(node, root_ / "class/video4linux" / name);
    }

    std::string root() const { return root_.string(); }

private:
    std::filesystem::path root_;

    std::filesystem::path device_dir(const std::string& port) const { return root_ / "devices/pci0000:00/usb1" / port; }
    static void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text << "\n"; }
};

}  // namespace vkfuse::test

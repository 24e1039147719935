// The DIGIT's LED control values per firmware, and discovery through a sysfs
// tree laid out as Linux lays out USB cameras.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "fake_sysfs.hpp"
#include "temp_dir.hpp"
#include "vkfuse/sensor/digit.hpp"
#include "vkfuse/sensor/digit_sensor.hpp"

namespace vkfuse::test {
namespace {

TEST(Digit, FirmwareFromBcdDevice) {
    EXPECT_EQ(DigitFirmware::from_bcd("0200")->to_string(), "2.00");
    EXPECT_EQ(DigitFirmware::from_bcd("0105")->to_string(), "1.05");
    EXPECT_EQ(DigitFirmware::from_bcd("1210")->major, 12);
    EXPECT_TRUE(DigitFirmware::from_bcd("0200")->per_led_levels());
    EXPECT_FALSE(DigitFirmware::from_bcd("0199")->per_led_levels());
    for (const char* bad : {"", "200", "02000", "02x0", "020a"}) EXPECT_FALSE(DigitFirmware::from_bcd(bad)) << bad;
}

TEST(Digit, LedValuesPerFirmware) {
    const DigitFirmware v2{2, 0}, v1{1, 0};
    const ControlRange packed{0, 0xfff}, intensity{1, 255}, with_off{0, 255};
    EXPECT_EQ(digit_led_value(Illumination({15, 15, 15}), v2, packed), 0xfff);
    EXPECT_EQ(digit_led_value(Illumination({0, 15, 0}), v2, packed), 0x0f0);
    EXPECT_EQ(digit_led_value(Illumination({1, 2, 3}), v2, packed), 0x123);
    EXPECT_EQ(digit_led_value(Illumination({0, 0, 0}), v2, packed), 0);
    EXPECT_EQ(digit_led_value(Illumination({15, 15, 15}), v1, intensity), 255);
    EXPECT_EQ(digit_led_value(Illumination({5, 5, 5}), v1, intensity), 85);
    EXPECT_EQ(digit_led_value(Illumination({0, 0, 0}), v1, with_off), 0);
    // Old firmware drives the LEDs alike and, where its minimum is 1, cannot
    // switch them off: refused, never sent as something else.
    expect_error([&] { digit_led_value(Illumination({0, 15, 0}), v1, intensity); }, "illumination 0,15,0",
                 ErrorKind::InvalidArgument, "DIGIT firmware 1.00 drives its three LEDs alike");
    expect_error([&] { digit_led_value(Illumination({0, 0, 0}), v1, intensity); }, "illumination 0,0,0",
                 ErrorKind::InvalidArgument, "takes LED values 1..255, not 0");
    // The range the device reports is obeyed, not assumed.
    expect_error([&] { digit_led_value(Illumination({15, 0, 0}), v2, ControlRange{0, 255}); }, "illumination 15,0,0",
                 ErrorKind::InvalidArgument, "takes LED values 0..255, not 3840");
    expect_error([&] { digit_led_value(Illumination({16, 0, 0}), v2, packed); }, "illumination 16,0,0",
                 ErrorKind::InvalidArgument, "exceeds 15");
}

TEST(Digit, LedSettingReadsBackWhatLedValueSends) {
    const DigitFirmware v2{2, 0}, v1{1, 0};
    const ControlRange packed{0, 0xfff}, with_off{0, 255};
    for (int r = 0; r <= 15; ++r)
        for (int g = 0; g <= 15; g += 5)
            for (int b = 0; b <= 15; b += 3) {
                const Illumination s({r, g, b});
                EXPECT_EQ(digit_led_setting(digit_led_value(s, v2, packed), v2, packed).to_string(), s.to_string());
            }
    for (int level = 0; level <= 15; ++level) {
        const Illumination s({level, level, level});
        EXPECT_EQ(digit_led_setting(digit_led_value(s, v1, with_off), v1, with_off).to_string(), s.to_string());
    }
    // Values the firmware clamps to its range light what the clamped value does.
    EXPECT_EQ(digit_led_setting(0x1fff, v2, packed).to_string(), "15,15,15");
    EXPECT_EQ(digit_led_setting(300, v1, with_off).to_string(), "15,15,15");
}

TEST(Digit, DiscoveryFindsDigitsTheirNodesAndBootloaders) {
    TempDir tmp;
    FakeSysfs sys(tmp.file("sys"));
    sys.add_usb("1-1", "2833", "0209", "D20002", "0200");
    sys.add_video("1-1", "video2", 0);
    sys.add_video("1-1", "video3", 1);  // its metadata node
    sys.add_usb("1-2", "2833", "0209", "D00001", "0105");
    sys.add_video("1-2", "video0", 0);
    sys.add_video("1-2", "video1", 1);
    sys.add_usb("1-3", "0403", "0fde", "", "0100");  // a DIGIT in its bootloader
    sys.add_usb("1-4", "046d", "0825", "WEBCAM", "0010");  // another camera
    sys.add_video("1-4", "video4", 0);
    DigitDiscovery where;
    where.sysfs = sys.root();
    where.dev = "/dev";
    std::vector<std::string> asked;
    where.is_capture = [&](const std::string& node) {
        asked.push_back(node);
        return node == "/dev/video0" || node == "/dev/video2";
    };
    const std::vector<DigitDevice> found = find_digits(where);
    ASSERT_EQ(found.size(), 3u);
    EXPECT_TRUE(found[0].bootloader);
    EXPECT_EQ(found[0].serial, "");
    EXPECT_EQ(found[0].usb_port, "1-3");
    EXPECT_TRUE(found[0].video_nodes.empty());
    EXPECT_EQ(found[1].serial, "D00001");
    EXPECT_EQ(found[1].firmware.to_string(), "1.05");
    EXPECT_EQ(found[1].video_nodes, std::vector<std::string>{"/dev/video0"});
    EXPECT_EQ(found[2].serial, "D20002");
    EXPECT_EQ(found[2].usb_port, "1-1");
    EXPECT_EQ(found[2].firmware.to_string(), "2.00");
    EXPECT_EQ(found[2].video_nodes, std::vector<std::string>{"/dev/video2"});
    // The other camera's node is never probed.
    EXPECT_EQ(std::count(asked.begin(), asked.end(), "/dev/video4"), 0);

    // Without a probe, a node that cannot be opened counts as the capture
    // node when it is its interface's first (index 0).
    where.dev = tmp.file("no-dev");
    where.is_capture = nullptr;
    const std::vector<DigitDevice> by_index = find_digits(where);
    ASSERT_EQ(by_index.size(), 3u);
    EXPECT_EQ(by_index[2].video_nodes, std::vector<std::string>{tmp.file("no-dev/video2")});
}

// Opening a DIGIT that is not there fails at once with one line naming it;
// the streaming itself is tested against an emulated DIGIT (ctest -L hil).
TEST(Digit, OpeningWhatIsNotThereNamesIt) {
    TempDir tmp;
    FakeSysfs sys(tmp.file("sys"));
    sys.add_usb("1-1", "2833", "0209", "D20002", "0200");
    sys.add_video("1-1", "video2", 0);
    sys.add_usb("1-3", "0403", "0fde", "", "0100");
    DigitOptions o;
    o.where.sysfs = sys.root();
    o.where.dev = tmp.file("dev");  // the node the sysfs tree names does not exist
    o.device = "D99999";
    expect_error([&] { DigitSensor s(o); }, "D99999", ErrorKind::InvalidArgument,
                 "no DIGIT with this serial is plugged in (found D20002; one is in its bootloader)");
    o.device = "/dev/video7";
    expect_error([&] { DigitSensor s(o); }, "/dev/video7", ErrorKind::InvalidArgument,
                 "not the capture node of a DIGIT (USB 2833:0209)");
    o.device = "D20002";
    expect_error([&] { DigitSensor s(o); }, "D20002", ErrorKind::Unplugged,
                 "cannot open " + tmp.file("dev/video2"));
    o.device = "";
    expect_error([&] { DigitSensor s(o); }, "DIGIT", ErrorKind::InvalidArgument, "no serial or video node");
    o.device = "D20002";
    o.timeout_s = 0;
    expect_error([&] { DigitSensor s(o); }, "D20002", ErrorKind::InvalidArgument, "timeout must be > 0");
}

TEST(Digit, ModesAndEncodingsReadAndPrint) {
    EXPECT_EQ(DigitMode{}.to_string(), "yuyv 320x240@60");
    EXPECT_EQ((DigitMode{640, 480, 15, DigitEncoding::Mjpeg}.to_string()), "mjpeg 640x480@15");
    EXPECT_EQ(parse_digit_encoding("mjpeg"), DigitEncoding::Mjpeg);
    EXPECT_EQ(parse_digit_encoding("yuyv"), DigitEncoding::Yuyv);
    expect_error([] { parse_digit_encoding("h264"); }, "--encoding", ErrorKind::InvalidArgument,
                 "unknown encoding 'h264' (yuyv or mjpeg)");
    EXPECT_TRUE(digit_modes("/nonexistent/video0").empty());
}

TEST(Digit, NoUsbNoDigits) {
    TempDir tmp;
    DigitDiscovery where;
    where.sysfs = tmp.file("missing");
    EXPECT_TRUE(find_digits(where).empty());
}

}  // namespace
}  // namespace vkfuse::test

// vkfuse devices: the DIGITs a (fake) sysfs tree holds, or one line saying
// there are none.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "fake_sysfs.hpp"

namespace vkfuse::test {
namespace {

TEST(CliDevices, NoDigitIsSaidOnceAndIsNoError) {
    TempDir tmp;
    FakeSysfs sys(tmp.file("sys"));
    sys.add_usb("1-4", "046d", "0825", "WEBCAM", "0010");
    const CliResult r = run_cli({"devices", "--sysfs", sys.root()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "vkfuse devices: no DIGIT found (USB 2833:0209 under " + sys.root() + "/bus/usb/devices)\n");
}

TEST(CliDevices, EachDigitIsOneJsonLine) {
    TempDir tmp;
    FakeSysfs sys(tmp.file("sys"));
    sys.add_usb("3-2", "2833", "0209", "D20417", "0200");
    sys.add_video("3-2", "video90", 0);
    sys.add_video("3-2", "video91", 1);
    sys.add_usb("3-3", "0403", "0fde", "", "0100");
    const CliResult r = run_cli({"devices", "--sysfs", sys.root()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out,
              "{\"serial\": \"\", \"usb\": \"3-3\", \"firmware\": \"1.00\", \"bootloader\": true, \"video_nodes\": [], "
              "\"modes\": []}\n"
              "{\"serial\": \"D20417\", \"usb\": \"3-2\", \"firmware\": \"2.00\", \"bootloader\": false, "
              "\"video_nodes\": [\"/dev/video90\"], \"modes\": []}\n");
}

TEST(CliDevices, ThisMachineIsListedWithoutError) {
    const CliResult r = run_cli({"devices"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(!r.out.empty() || r.err.find("no DIGIT found") != std::string::npos) << r.err;
}

TEST(CliDevices, OperandsAreRefused) {
    const CliResult r = run_cli({"devices", "D20417"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err_lines().size(), 1u) << r.err;
}

}  // namespace
}  // namespace vkfuse::test

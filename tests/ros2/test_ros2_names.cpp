// ROS 2 names and the message generator, as hostile input meets them: a
// serial of any characters becomes a valid topic token; domains and
// encodings are checked as ROS 2 reads them; two serials that would share a
// topic are refused; a .msg file the generator cannot map is refused with
// its file and line, and nothing is written.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "expect_error.hpp"
#include "temp_dir.hpp"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::test {
namespace {

// ROS 2's rule for a name's token: [A-Za-z_][A-Za-z0-9_]*.
bool valid_token(const std::string& t) {
    if (t.empty() || std::isdigit(static_cast<unsigned char>(t[0]))) return false;
    for (char c : t)
        if (!(std::isalnum(static_cast<unsigned char>(c)) && c >= 0) && c != '_') return false;
    return true;
}

TEST(Ros2Names, EverySerialBecomesAValidToken) {
    EXPECT_EQ(ros2::topic_token("SIM-0001"), "SIM_0001");
    EXPECT_EQ(ros2::topic_token("D20001"), "D20001");
    EXPECT_EQ(ros2::topic_token("2023.7"), "sensor_2023_7");
    EXPECT_EQ(ros2::topic_token(""), "sensor_");
    EXPECT_EQ(ros2::topic_token("a/../b c"), "a____b_c");
    for (const std::string serial : {"SIM-0001", "0", "/", "\xc3\xa9t\xc3\xa9", "x y", "..", "_", "9lives"})
        EXPECT_TRUE(valid_token(ros2::topic_token(serial))) << serial;
}

TEST(Ros2Names, DomainsAndEncodingsAreCheckedAsRos2ReadsThem) {
    EXPECT_EQ(ros2::parse_domain("0"), 0);
    EXPECT_EQ(ros2::parse_domain("232"), 232);
    for (const char* bad : {"", "233", "-1", "7x", " 7", "0x10", "1000", "99999999999999999999"})
        EXPECT_FALSE(ros2::parse_domain(bad)) << bad;
    EXPECT_EQ(ros2::parse_image_encoding("rgb8"), ros2::ImageEncoding::Rgb8);
    EXPECT_EQ(ros2::parse_image_encoding("32FC3"), ros2::ImageEncoding::Float32);
    EXPECT_FALSE(ros2::parse_image_encoding("bgr8"));
    EXPECT_EQ(method_label(FusionSpec{}), "wavelet/bior4.4");
    FusionSpec brovey;
    brovey.method = Method::Brovey;
    EXPECT_EQ(method_label(brovey), "brovey");
}

TEST(Ros2Names, SerialsSharingATopicAreRefused) {
    ros2::RigTopics rig;
    for (const char* serial : {"SIM-0001", "SIM_0001"}) {
        SensorInfo info;
        info.serial = serial;
        info.width = 320;
        info.height = 240;
        info.leds = LedLayout::digit();
        rig.sensors.push_back(info);
    }
    rig.sequence = parse_sequence("15,15,15");
    expect_error([&] { ros2::RigPublisher p(rig, {}); }, "--publish ros2", ErrorKind::InvalidArgument,
                 "serials SIM-0001 and SIM_0001 both name topics /vkfuse/SIM_0001");
    rig.sensors.pop_back();
    expect_error([&] { ros2::RigPublisher p(rig, {233, ros2::ImageEncoding::Rgb8}); }, "ROS domain 233",
                 ErrorKind::InvalidArgument, "expected 0..232");
}

// msg_to_idl on one .msg file: its exit status, and its one line on stderr.
struct Generated {
    int status;
    std::string err;
    bool wrote;
};
Generated generate(const std::string& name, const std::string& text) {
    TempDir dir;
    const std::string msg = dir.file(name), idl = dir.file("out.idl"), err = dir.file("stderr");
    std::ofstream(msg) << text;
    const std::string command = std::string(VKFUSE_MSG_TO_IDL) + " " + idl + " pkg " + msg + " 2>" + err;
    const int rc = std::system(command.c_str());
    return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, read_bytes(err), std::filesystem::exists(idl)};
}

TEST(Ros2MsgToIdl, MapsRos2TypesAsRosidlDoes) {
    TempDir dir;
    std::ofstream(dir.file("Inner.msg")) << "float32[3] xyz\n";
    std::ofstream(dir.file("Outer.msg")) << "# comment\nuint8 A=1  # constant\nInner[<=4] inner\nstring<=8 name\n"
                                            "byte b\nchar c\nHeader header\nsensor_msgs/Image[] images\nbool ok\n";
    const std::string idl = dir.file("pkg.idl");
    const std::string command = std::string(VKFUSE_MSG_TO_IDL) + " " + idl + " pkg " + dir.file("Outer.msg") + " " +
                                dir.file("Inner.msg");
    ASSERT_EQ(std::system(command.c_str()), 0);
    const std::string text = read_bytes(idl);
    // Inner comes first (Outer holds it), whatever the order given.
    EXPECT_LT(text.find("struct Inner_"), text.find("struct Outer_"));
    for (const char* line : {"#include \"sensor_msgs.idl\"", "#include \"std_msgs.idl\"", "float xyz[3];",
                             "const uint8 A = 1;", "sequence<pkg::msg::dds_::Inner_, 4> inner;", "string<8> name;",
                             "octet b;", "uint8 c;", "std_msgs::msg::dds_::Header_ header;",
                             "sequence<sensor_msgs::msg::dds_::Image_> images;", "boolean ok;"})
        EXPECT_NE(text.find(line), std::string::npos) << line << "\n" << text;
}

TEST(Ros2MsgToIdl, WhatCannotBeMappedIsRefusedWithItsLine) {
    const struct {
        const char* text;
        const char* problem;
    } cases[] = {
        {"int32 x\nint32 sequence\n", ":2: field name sequence is an IDL keyword"},
        {"int32 x 5\n", ":1: default values are not supported: 'int32 x 5'"},
        {"int32 9x\n", ":1: bad field name in 'int32 9x'"},
        {"Missing m\n", ": uses Missing, which is not among the package's messages"},
        {"Bad holds\n", ": holds itself through its fields"},
        {"int32[x] a\n", ": bad array [x]"},
        {"bad-pkg/T t\n", ":1: unknown type bad-pkg/T"},
        {"string S=\"a\"\n", ":1: unsupported constant 'string S=\"a\"'"},
    };
    for (const auto& c : cases) {
        const Generated g = generate("Bad.msg", c.text);
        EXPECT_EQ(g.status, 1) << c.text;
        EXPECT_NE(g.err.find(c.problem), std::string::npos) << c.text << " gave: " << g.err;
        EXPECT_EQ(g.err.rfind("msg_to_idl: ", 0), 0u) << g.err;
        EXPECT_FALSE(g.wrote) << c.text;
    }
}

}  // namespace
}  // namespace vkfuse::test

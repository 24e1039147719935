// The Digit 360's LEDs over a pseudo-terminal that reads what a Digit 360
// reads: COBS frames (or bare messages) holding Digit360Message protobufs,
// decoded here by an independent reader of the wire format.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include "expect_error.hpp"
#include "vkfuse/sensor/digit360.hpp"

namespace vkfuse::test {
namespace {

// The device's side of a serial port.
class FakePort {
public:
    FakePort() {
        master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
        EXPECT_GE(master_, 0);
        EXPECT_EQ(::grantpt(master_), 0);
        EXPECT_EQ(::unlockpt(master_), 0);
        name_ = ::ptsname(master_);
    }
    ~FakePort() { ::close(master_); }
    const std::string& name() const { return name_; }

    // Everything written so far (waits up to 1 s for the first byte).
    std::vector<std::uint8_t> read_all() {
        std::vector<std::uint8_t> out;
        for (int wait_ms = 1000;; wait_ms = 50) {
            pollfd p{master_, POLLIN, 0};
            if (::poll(&p, 1, wait_ms) <= 0) break;
            std::uint8_t buf[4096];
            const ssize_t n = ::read(master_, buf, sizeof buf);
            if (n <= 0) break;
            out.insert(out.end(), buf, buf + n);
        }
        return out;
    }

private:
    int master_ = -1;
    std::string name_;
};

// LightingControl's fields as a protobuf reader sees them.
struct Lighting {
    float alpha = 0;
    std::map<int, std::uint64_t> ints;  // field number -> varint
};

std::uint64_t read_varint(const std::vector<std::uint8_t>& b, std::size_t& i) {
    std::uint64_t v = 0;
    for (int shift = 0; i < b.size(); shift += 7) {
        const std::uint8_t byte = b[i++];
        v |= std::uint64_t(byte & 0x7f) << shift;
        if (!(byte & 0x80)) return v;
    }
    ADD_FAILURE() << "varint runs off the end";
    return v;
}

std::optional<Lighting> parse_message(const std::vector<std::uint8_t>& m) {
    std::size_t i = 0;
    if (read_varint(m, i) != ((7u << 3) | 2u)) return std::nullopt;  // field 7, length-delimited
    const std::size_t len = read_varint(m, i);
    if (i + len != m.size()) return std::nullopt;
    Lighting out;
    while (i < m.size()) {
        const std::uint64_t key = read_varint(m, i);
        if ((key & 7) == 5) {
            std::uint32_t bits = 0;
            for (int k = 0; k < 4; ++k) bits |= std::uint32_t(m[i++]) << (8 * k);
            if ((key >> 3) == 1) std::memcpy(&out.alpha, &bits, 4);
        } else if ((key & 7) == 0) {
            out.ints[int(key >> 3)] = read_varint(m, i);
        } else {
            return std::nullopt;
        }
    }
    return out;
}

std::vector<Lighting> cobs_messages(const std::vector<std::uint8_t>& wire) {
    std::vector<Lighting> out;
    std::vector<std::uint8_t> frame, data;
    for (std::uint8_t byte : wire) {
        if (byte != 0) {
            frame.push_back(byte);
            continue;
        }
        EXPECT_TRUE(cobs_decode(frame, data));
        const auto m = parse_message(data);
        EXPECT_TRUE(m.has_value());
        if (m) out.push_back(*m);
        frame.clear();
    }
    EXPECT_TRUE(frame.empty()) << "bytes after the last delimiter";
    return out;
}

Illumination eight(std::vector<int> per_led_rgb) {
    std::vector<int> levels;
    for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 3; ++c) levels.push_back(per_led_rgb[std::size_t((3 * i + c) % per_led_rgb.size())]);
    return Illumination(levels);
}

TEST(Digit360, CobsRoundTripsEveryByteAndLongRuns) {
    std::vector<std::vector<std::uint8_t>> cases = {{}, {0}, {0, 0}, {1, 2, 0, 3}, {0x11, 0x22, 0x00, 0x33}};
    std::vector<std::uint8_t> long_run(600);
    for (std::size_t i = 0; i < long_run.size(); ++i) long_run[i] = std::uint8_t(i % 7 == 0 ? 0 : i);
    cases.push_back(long_run);
    cases.push_back(std::vector<std::uint8_t>(300, 0xab));  // blocks of 254 without a zero
    for (const auto& data : cases) {
        const std::vector<std::uint8_t> wire = cobs_encode(data);
        ASSERT_EQ(wire.back(), 0);
        for (std::size_t i = 0; i + 1 < wire.size(); ++i) ASSERT_NE(wire[i], 0) << "a zero inside the frame";
        std::vector<std::uint8_t> back;
        ASSERT_TRUE(cobs_decode({wire.data(), wire.size() - 1}, back));
        EXPECT_EQ(back, data);
    }
    // The textbook example: 11 22 00 33 -> 03 11 22 02 33 00.
    EXPECT_EQ(cobs_encode(std::vector<std::uint8_t>{0x11, 0x22, 0x00, 0x33}),
              (std::vector<std::uint8_t>{0x03, 0x11, 0x22, 0x02, 0x33, 0x00}));
    std::vector<std::uint8_t> out;
    EXPECT_FALSE(cobs_decode(std::vector<std::uint8_t>{0x05, 0x11}, out));  // the block runs past the end
}

TEST(Digit360, EachLedGetsItsOwnMessageOverThePort) {
    FakePort port;
    Digit360Leds leds({port.name(), Digit360Framing::Cobs, 255.0f, 0.5});
    std::vector<int> levels(24);
    for (int i = 0; i < 24; ++i) levels[std::size_t(i)] = (i * 37) % 256;
    leds.set(Illumination(levels));
    const std::vector<Lighting> got = cobs_messages(port.read_all());
    ASSERT_EQ(got.size(), 8u);
    for (int led = 0; led < 8; ++led) {
        const Lighting& m = got[std::size_t(led)];
        EXPECT_EQ(m.alpha, 255.0f);
        EXPECT_EQ(m.ints.at(2), std::uint64_t(led + 1)) << "LightingChannel CHANNEL_" << led + 1;
        for (int c = 0; c < 3; ++c) {
            const int want = levels[std::size_t(3 * led + c)];
            const auto it = m.ints.find(3 + c);
            EXPECT_EQ(it == m.ints.end() ? 0 : int(it->second), want) << "led " << led << " colour " << c;
        }
    }
}

TEST(Digit360, AlikeLedsTakeOneMessageForAll) {
    FakePort port;
    Digit360Leds leds({port.name(), Digit360Framing::Cobs, 255.0f, 0.5});
    leds.set(eight({0, 200, 15}));
    const std::vector<Lighting> got = cobs_messages(port.read_all());
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].ints.at(2), 9u);  // CHANNEL_ALL
    EXPECT_EQ(got[0].ints.count(3), 0u) << "proto3 leaves a zero field out";
    EXPECT_EQ(got[0].ints.at(4), 200u);
    EXPECT_EQ(got[0].ints.at(5), 15u);
}

TEST(Digit360, RawFramingSendsTheBareMessage) {
    FakePort port;
    Digit360Leds leds({port.name(), Digit360Framing::Raw, 0.0f, 0.5});
    leds.set(eight({255, 0, 0}));
    const std::vector<std::uint8_t> wire = port.read_all();
    // field 7, length 5: channel 9, r 255 (varint ff 01); alpha 0 is left out.
    EXPECT_EQ(wire, (std::vector<std::uint8_t>{0x3a, 0x05, 0x10, 0x09, 0x18, 0xff, 0x01}));
}

TEST(Digit360, SettingsOutsideTheLayoutAndBadPortsAreRefused) {
    FakePort port;
    Digit360Leds leds({port.name(), Digit360Framing::Cobs, 255.0f, 0.5});
    expect_error([&] { leds.set(Illumination({15, 15, 15})); }, "illumination 15,15,15", ErrorKind::InvalidArgument,
                 "3 levels, Digit360 has 24 LED channels");
    const Illumination too_bright = eight({256, 0, 0});
    expect_error([&] { leds.set(too_bright); }, "illumination " + too_bright.to_string(), ErrorKind::InvalidArgument,
                 "level 256 of led0.r exceeds 255");
    EXPECT_TRUE(port.read_all().empty()) << "nothing is sent for a refused setting";
    expect_error([] { Digit360Leds bad({"/nonexistent/ttyACM9"}); }, "/nonexistent/ttyACM9", ErrorKind::Device,
                 "cannot open");
    expect_error([] { Digit360Leds bad({"/dev/null"}); }, "/dev/null", ErrorKind::Device, "not a serial port");
}

TEST(Digit360, APortThatTakesNothingIsATimeoutNotAHang) {
    FakePort port;  // never read: the terminal's buffer fills
    Digit360Leds leds({port.name(), Digit360Framing::Cobs, 255.0f, 0.2});
    std::vector<int> levels(24);
    bool timed_out = false;
    for (int i = 0; i < 100000 && !timed_out; ++i) {
        levels[std::size_t(i % 24)] = i % 256;
        try {
            leds.set(Illumination(levels));
        } catch (const Error& e) {
            timed_out = e.kind() == ErrorKind::Timeout;
            EXPECT_EQ(std::string(e.what()).rfind(port.name() + ": took nothing for", 0), 0u) << e.what();
        }
    }
    EXPECT_TRUE(timed_out);
}

}  // namespace
}  // namespace vkfuse::test

// The Digit 360's LED messages and serial port (vkfuse/sensor/digit360.hpp).
#include "vkfuse/sensor/digit360.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

constexpr int kLeds = 8;
constexpr std::uint32_t kChannelAll = 9;  // LightingChannel.CHANNEL_ALL
constexpr std::uint32_t kLightingControlField = 7;  // Digit360Message.lighting_control

void varint(std::vector<std::uint8_t>& out, std::uint64_t v) {
    do {
        std::uint8_t byte = std::uint8_t(v & 0x7f);
        v >>= 7;
        if (v) byte |= 0x80;
        out.push_back(byte);
    } while (v);
}

void tag(std::vector<std::uint8_t>& out, std::uint32_t field, std::uint32_t wire_type) {
    varint(out, (std::uint64_t(field) << 3) | wire_type);
}

// A proto3 int32/enum field: absent at 0.
void int_field(std::vector<std::uint8_t>& out, std::uint32_t field, std::int32_t v) {
    if (v == 0) return;
    tag(out, field, 0);
    varint(out, std::uint64_t(std::int64_t(v)));  // negative int32 takes ten bytes, as protobuf says
}

std::vector<std::uint8_t> lighting_message(float alpha, std::uint32_t channel, int r, int g, int b) {
    std::vector<std::uint8_t> control;
    if (alpha != 0.0f) {
        tag(control, 1, 5);  // fixed32
        std::uint32_t bits;
        std::memcpy(&bits, &alpha, 4);
        for (int i = 0; i < 4; ++i) control.push_back(std::uint8_t(bits >> (8 * i)));
    }
    int_field(control, 2, std::int32_t(channel));
    int_field(control, 3, r);
    int_field(control, 4, g);
    int_field(control, 5, b);
    std::vector<std::uint8_t> message;
    tag(message, kLightingControlField, 2);  // length-delimited
    varint(message, control.size());
    message.insert(message.end(), control.begin(), control.end());
    return message;
}

}  // namespace

std::vector<std::vector<std::uint8_t>> digit360_lighting_messages(const Illumination& setting, float alpha) {
    setting.check(LedLayout::digit360());
    const auto led = [&](int i, int c) { return setting.level(3 * i + c); };
    bool alike = true;
    for (int i = 1; i < kLeds; ++i)
        for (int c = 0; c < 3; ++c) alike = alike && led(i, c) == led(0, c);
    std::vector<std::vector<std::uint8_t>> out;
    if (alike) {
        out.push_back(lighting_message(alpha, kChannelAll, led(0, 0), led(0, 1), led(0, 2)));
        return out;
    }
    for (int i = 0; i < kLeds; ++i)
        out.push_back(lighting_message(alpha, std::uint32_t(i + 1), led(i, 0), led(i, 1), led(i, 2)));
    return out;
}

std::vector<std::uint8_t> cobs_encode(std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> out;
    out.reserve(data.size() + data.size() / 254 + 2);
    std::size_t code_at = out.size();
    out.push_back(0);
    std::uint8_t code = 1;
    for (std::uint8_t byte : data) {
        if (byte != 0) {
            out.push_back(byte);
            ++code;
        }
        if (byte == 0 || code == 0xff) {
            out[code_at] = code;
            code_at = out.size();
            out.push_back(0);
            code = 1;
        }
    }
    out[code_at] = code;
    out.push_back(0);  // the delimiter
    return out;
}

bool cobs_decode(std::span<const std::uint8_t> frame, std::vector<std::uint8_t>& data) {
    data.clear();
    for (std::size_t i = 0; i < frame.size();) {
        const std::uint8_t code = frame[i++];
        if (code == 0 || i + code - 1 > frame.size()) return false;
        for (std::uint8_t k = 1; k < code; ++k) {
            if (frame[i] == 0) return false;
            data.push_back(frame[i++]);
        }
        if (code != 0xff && i < frame.size()) data.push_back(0);
    }
    return true;
}

Digit360Leds::Digit360Leds(const Digit360LedOptions& options) : options_(options) {
    fd_ = ::open(options.tty.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) throw Error(ErrorKind::Device, options.tty + ": cannot open: " + std::strerror(errno));
    termios t{};
    if (::tcgetattr(fd_, &t) != 0) {
        const int err = errno;
        ::close(fd_);
        throw Error(ErrorKind::Device, options.tty + ": not a serial port: " + std::strerror(err));
    }
    ::cfmakeraw(&t);
    t.c_cflag |= CLOCAL | CREAD;
    if (::tcsetattr(fd_, TCSANOW, &t) != 0) {
        const int err = errno;
        ::close(fd_);
        throw Error(ErrorKind::Device, options.tty + ": cannot set raw mode: " + std::strerror(err));
    }
}

Digit360Leds::~Digit360Leds() {
    if (fd_ >= 0) ::close(fd_);
}

void Digit360Leds::write_all(std::span<const std::uint8_t> bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
        if (n > 0) {
            done += std::size_t(n);
            continue;
        }
        if (n < 0 && errno != EAGAIN && errno != EINTR) {
            const int err = errno;
            const bool gone = err == EIO || err == ENODEV || err == ENXIO;
            throw Error(gone ? ErrorKind::Unplugged : ErrorKind::Device,
                        options_.tty + ": " + (gone ? "unplugged" : "write failed") + ": " + std::strerror(err));
        }
        pollfd p{fd_, POLLOUT, 0};
        const int r = ::poll(&p, 1, int(std::ceil(options_.write_timeout_s * 1000)));
        if (r == 0)
            throw Error(ErrorKind::Timeout, options_.tty + ": took nothing for " +
                                                std::to_string(options_.write_timeout_s) + " s");
        if (r > 0 && (p.revents & (POLLERR | POLLHUP)))
            throw Error(ErrorKind::Unplugged, options_.tty + ": unplugged (the port hung up)");
    }
}

void Digit360Leds::set(const Illumination& setting) {
    for (const std::vector<std::uint8_t>& message : digit360_lighting_messages(setting, options_.alpha))
        write_all(options_.framing == Digit360Framing::Cobs ? cobs_encode(message) : message);
}

}  // namespace vkfuse

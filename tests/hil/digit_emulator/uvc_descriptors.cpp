// The emulated DIGIT's descriptors (uvc_descriptors.hpp), laid out as the USB
// 2.0 and UVC 1.1 specifications give them; multi-byte fields little-endian.
#include "uvc_descriptors.hpp"

namespace vkfuse::emulator {
namespace {

class Bytes {
public:
    Bytes& u8(unsigned v) {
        b.push_back(std::uint8_t(v));
        return *this;
    }
    Bytes& u16(unsigned v) { return u8(v & 0xff).u8(v >> 8); }
    Bytes& u32(std::uint32_t v) { return u16(v & 0xffff).u16(v >> 16); }
    Bytes& add(const std::vector<std::uint8_t>& more) {
        b.insert(b.end(), more.begin(), more.end());
        return *this;
    }
    std::vector<std::uint8_t> b;
};

constexpr std::uint8_t kCsInterface = 0x24;
constexpr std::uint8_t kOutputTerminalId = 2;

std::vector<std::uint8_t> frame(const StreamMode& m) {
    Bytes f;
    f.u8(26 + 4 * m.intervals.size()).u8(kCsInterface).u8(m.mjpeg ? 0x07 : 0x05).u8(m.frame_index).u8(0);
    f.u16(m.width).u16(m.height);
    const std::uint32_t bits = m.max_frame_bytes() * 8;
    f.u32(bits * std::uint32_t(1e7 / m.intervals.back())).u32(bits * std::uint32_t(1e7 / m.intervals.front()));
    f.u32(m.max_frame_bytes()).u32(m.intervals.front()).u8(m.intervals.size());
    for (std::uint32_t i : m.intervals) f.u32(i);
    return f.b;
}

std::vector<std::uint8_t> streaming_formats() {
    const std::vector<StreamMode> modes = digit_stream_modes();
    Bytes out;
    for (const bool mjpeg : {false, true}) {
        int frames = 0;
        for (const StreamMode& m : modes) frames += m.mjpeg == mjpeg;
        if (!mjpeg) {
            static const std::uint8_t yuy2[16] = {'Y', 'U', 'Y', '2', 0x00, 0x00, 0x10, 0x00,
                                                  0x80, 0x00, 0x00, 0xaa, 0x00, 0x38, 0x9b, 0x71};
            out.u8(27).u8(kCsInterface).u8(0x04).u8(1).u8(frames);
            for (std::uint8_t g : yuy2) out.u8(g);
            out.u8(16).u8(1).u8(0).u8(0).u8(0).u8(0);
        } else {
            out.u8(11).u8(kCsInterface).u8(0x06).u8(2).u8(frames).u8(1).u8(1).u8(0).u8(0).u8(0).u8(0);
        }
        for (const StreamMode& m : modes)
            if (m.mjpeg == mjpeg) out.add(frame(m));
    }
    return out.b;
}

}  // namespace

std::vector<StreamMode> digit_stream_modes() {
    std::vector<StreamMode> out;
    for (const bool mjpeg : {false, true}) {
        out.push_back({mjpeg ? 2 : 1, 1, mjpeg, 320, 240, {10000000 / 60, 10000000 / 30}});
        out.push_back({mjpeg ? 2 : 1, 2, mjpeg, 640, 480, {10000000 / 30, 10000000 / 15}});
    }
    return out;
}

std::vector<std::uint8_t> device_descriptor(std::uint16_t bcd_device) {
    Bytes d;
    // Class per interface: a device with one function needs no interface association.
    d.u8(18).u8(1).u16(0x0200).u8(0).u8(0).u8(0).u8(64);
    d.u16(0x2833).u16(0x0209).u16(bcd_device).u8(1).u8(2).u8(3).u8(1);
    return d.b;
}

std::vector<std::uint8_t> device_qualifier() {
    Bytes q;
    q.u8(10).u8(6).u16(0x0200).u8(0).u8(0).u8(0).u8(64).u8(1).u8(0);
    return q.b;
}

std::vector<std::uint8_t> endpoint_descriptor(bool high_speed) {
    Bytes e;
    e.u8(7).u8(5).u8(kStreamingEndpoint).u8(0x02).u16(high_speed ? 512 : 64).u8(0);
    return e.b;
}

// The layout is as lean as UVC 1.1 allows (no interface association, no
// colour matching, 2-byte camera controls, no per-format streaming controls):
// uvcvideo needs none of them.
std::vector<std::uint8_t> config_descriptor(bool high_speed) {
    Bytes vc;  // VideoControl class-specific descriptors
    const unsigned vc_total = 13 + 17 + 9;
    vc.u8(13).u8(kCsInterface).u8(0x01).u16(0x0110).u16(vc_total).u32(48000000).u8(1).u8(kStreamingInterface);
    vc.u8(17).u8(kCsInterface).u8(0x02).u8(kCameraTerminalId).u16(0x0201).u8(0).u8(0);
    vc.u16(0).u16(0).u16(0).u8(2).u8(0x00).u8(0x02);  // bmControls: D9, zoom (absolute)
    vc.u8(9).u8(kCsInterface).u8(0x03).u8(kOutputTerminalId).u16(0x0101).u8(0).u8(kCameraTerminalId).u8(0);

    const std::vector<std::uint8_t> formats = streaming_formats();
    Bytes vs;  // VideoStreaming input header, then the formats
    const unsigned vs_total = 13 + unsigned(formats.size());
    vs.u8(13).u8(kCsInterface).u8(0x01).u8(2).u16(vs_total).u8(kStreamingEndpoint).u8(0).u8(kOutputTerminalId);
    vs.u8(0).u8(0).u8(0).u8(0);  // no per-format controls (bControlSize 0)
    vs.add(formats);

    Bytes body;
    body.u8(9).u8(4).u8(kControlInterface).u8(0).u8(0).u8(0x0e).u8(0x01).u8(0).u8(0).add(vc.b);
    body.u8(9).u8(4).u8(kStreamingInterface).u8(0).u8(1).u8(0x0e).u8(0x02).u8(0).u8(0).add(vs.b);
    body.add(endpoint_descriptor(high_speed));

    Bytes config;
    config.u8(9).u8(2).u16(9 + unsigned(body.b.size())).u8(2).u8(1).u8(0).u8(0x80).u8(250).add(body.b);
    return config.b;
}

std::vector<std::uint8_t> streaming_control(const Committed& c) {
    Bytes b;
    b.u16(1);  // bmHint: dwFrameInterval fixed
    b.u8(c.mode.format_index).u8(c.mode.frame_index).u32(c.interval);
    b.u16(0).u16(0).u16(0).u16(0).u16(0);  // key frame rate, P frame rate, quality, window size, delay
    b.u32(c.mode.max_frame_bytes()).u32(c.mode.max_payload_bytes());
    b.u32(48000000);      // dwClockFrequency
    b.u8(3).u8(1).u8(1).u8(1);  // bmFramingInfo (FID and EOF used), preferred, min and max version
    return b.b;
}

std::vector<std::uint8_t> string_descriptor(int index, const std::string& serial) {
    if (index == 0) return {4, 3, 0x09, 0x04};
    const std::string text = index == 1 ? "vkfuse DIGIT emulator" : index == 2 ? "DIGIT" : serial;
    Bytes s;
    s.u8(2 + 2 * text.size()).u8(3);
    for (char c : text) s.u16(std::uint8_t(c));
    return s.b;
}

}  // namespace vkfuse::emulator

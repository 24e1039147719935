// uvc_descriptors.hpp - an emulated DIGIT's USB descriptors: the DIGIT's
// identity (2833:0209, "DIGIT", its serial, bcdDevice = firmware) and a UVC
// 1.1 camera whose camera terminal offers the zoom control (the LEDs) and
// whose streaming interface offers the DIGIT's modes in YUYV and MJPEG over
// a bulk endpoint.
//
//   config: VideoControl (header, camera terminal 1 [zoom], output terminal 2)
//           VideoStreaming alt 0 (input header, YUYV {qvga, vga}, MJPEG {qvga, vga}, bulk IN 0x81)
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vkfuse::emulator {

// One format/frame offered, with its UVC indices.
struct StreamMode {
    int format_index = 0;
    int frame_index = 0;
    bool mjpeg = false;
    int width = 0;
    int height = 0;
    std::vector<std::uint32_t> intervals;  // 100 ns units, first the default
    std::uint32_t max_frame_bytes() const { return std::uint32_t(width * height * 2); }
    // dwMaxPayloadTransferSize: a frame is one payload, its 2-byte header and the frame.
    std::uint32_t max_payload_bytes() const { return max_frame_bytes() + 2; }
};

// What the host committed to stream.
struct Committed {
    StreamMode mode;
    std::uint32_t interval = 0;  // 100 ns units
    double fps() const { return 1e7 / interval; }
};

// The DIGIT's modes: YUYV (format 1) and MJPEG (format 2), each QVGA at 60 or
// 30 fps (frame 1) and VGA at 30 or 15 (frame 2).
std::vector<StreamMode> digit_stream_modes();

inline constexpr std::uint8_t kCameraTerminalId = 1;
inline constexpr std::uint8_t kControlInterface = 0;
inline constexpr std::uint8_t kStreamingInterface = 1;
inline constexpr std::uint8_t kStreamingEndpoint = 0x81;

std::vector<std::uint8_t> device_descriptor(std::uint16_t bcd_device);
// The whole configuration descriptor; high_speed sets the bulk packet size.
std::vector<std::uint8_t> config_descriptor(bool high_speed);
std::vector<std::uint8_t> endpoint_descriptor(bool high_speed);
// What the device would be at full speed (a high-speed device's qualifier).
std::vector<std::uint8_t> device_qualifier();
// The UVC 1.1 probe/commit control block (34 bytes) for a committed mode:
// frame interval fixed, one payload per frame (dwMaxPayloadTransferSize).
std::vector<std::uint8_t> streaming_control(const Committed& c);
inline constexpr std::size_t kStreamingControlSize = 34;

// String descriptor `index` (0: the language list; 1 manufacturer, 2 "DIGIT", 3 serial).
std::vector<std::uint8_t> string_descriptor(int index, const std::string& serial);

}  // namespace vkfuse::emulator

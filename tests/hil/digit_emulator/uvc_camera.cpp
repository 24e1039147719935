// The emulated DIGIT as a USB device (uvc_camera.hpp): the control requests
// of USB 2.0 chapter 9 and UVC 1.1 that uvcvideo makes of a camera with one
// control, and the bulk payloads of its stream.
#include "uvc_camera.hpp"

#include <linux/usb/ch9.h>
#include <linux/usb/video.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace vkfuse::emulator {
namespace {

std::uint32_t get_u32(std::span<const std::uint8_t> in, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4 && at + i < in.size(); ++i) v |= std::uint32_t(in[at + i]) << (8 * i);
    return v;
}

ControlReply bytes(std::vector<std::uint8_t> data) { return {false, std::move(data)}; }
ControlReply u16(unsigned v) { return bytes({std::uint8_t(v), std::uint8_t(v >> 8)}); }
ControlReply done() { return {}; }

constexpr unsigned kStreamingEndpointNumber = kStreamingEndpoint & 0x0f;
constexpr double kPollS = 0.05;  // how often a frame waiting for the host looks whether it still streams

}  // namespace

UvcCamera::UvcCamera(const CameraSpec& spec, std::function<void(std::uint16_t)> on_zoom)
    : spec_(spec), on_zoom_(std::move(on_zoom)), zoom_value_(spec.zoom.default_value) {
    probe_ = commit_ = Committed{modes_.front(), modes_.front().intervals.front()};
    device_ = std::make_unique<UsbipDevice>([this](const SetupPacket& s, std::span<const std::uint8_t> out) {
        return control(s, out);
    }, spec_.vhci);
}

void UvcCamera::unplug() {
    {
        std::lock_guard lock(mutex_);
        streaming_ = false;
    }
    device_->unplug();
}

ControlReply UvcCamera::control(const SetupPacket& s, std::span<const std::uint8_t> out) {
    if (std::getenv("VKFUSE_EMULATOR_TRACE"))
        std::fprintf(stderr, "digit-emulator: setup %02x %02x %04x %04x %u\n", s.request_type, s.request, s.value,
                     s.index, s.length);
    const unsigned type = s.request_type & USB_TYPE_MASK;
    if (type == USB_TYPE_STANDARD) return standard_request(s);
    if (type != USB_TYPE_CLASS) return ControlReply::refuse();
    const int interface = s.index & 0xff, entity = s.index >> 8, selector = s.value >> 8;
    if (interface == kStreamingInterface && (selector == UVC_VS_PROBE_CONTROL || selector == UVC_VS_COMMIT_CONTROL))
        return streaming_request(s, out);
    if (interface == kControlInterface && entity == kCameraTerminalId && selector == UVC_CT_ZOOM_ABSOLUTE_CONTROL)
        return zoom_request(s, out);
    if (interface == kControlInterface && entity == 0 && selector == UVC_VC_REQUEST_ERROR_CODE_CONTROL && s.in()) {
        if (s.request == UVC_GET_CUR) return bytes({0x06});  // the last request named an invalid control
        if (s.request == UVC_GET_INFO) return bytes({0x01});
    }
    return ControlReply::refuse();
}

ControlReply UvcCamera::standard_request(const SetupPacket& s) {
    switch (s.request) {
        case USB_REQ_GET_DESCRIPTOR:
            switch (s.value >> 8) {
                case USB_DT_DEVICE: return bytes(device_descriptor(spec_.bcd_device));
                case USB_DT_CONFIG: return bytes(config_descriptor(true));
                case USB_DT_DEVICE_QUALIFIER: return bytes(device_qualifier());
                case USB_DT_STRING:
                    if ((s.value & 0xff) <= 3) return bytes(string_descriptor(s.value & 0xff, spec_.serial));
                    return ControlReply::refuse();
                default: return ControlReply::refuse();
            }
        case USB_REQ_SET_CONFIGURATION: {
            std::lock_guard lock(mutex_);
            streaming_ = false;
            return done();
        }
        case USB_REQ_GET_CONFIGURATION: return bytes({1});
        case USB_REQ_GET_INTERFACE: return bytes({0});
        case USB_REQ_GET_STATUS: return bytes({0, 0});
        case USB_REQ_CLEAR_FEATURE:
            // uvcvideo clears the halt of a bulk streaming endpoint when it stops streaming.
            if ((s.request_type & USB_RECIP_MASK) == USB_RECIP_ENDPOINT && (s.index & 0xff) == kStreamingEndpoint) {
                std::lock_guard lock(mutex_);
                streaming_ = false;
            }
            return done();
        case USB_REQ_SET_INTERFACE:
        case USB_REQ_SET_FEATURE: return done();
        default: return ControlReply::refuse();
    }
}

Committed UvcCamera::clamp(std::span<const std::uint8_t> probe) const {
    const int format = probe.size() > 2 ? probe[2] : 0, frame = probe.size() > 3 ? probe[3] : 0;
    const std::uint32_t interval = get_u32(probe, 4);
    const StreamMode* mode = &modes_.front();
    for (const StreamMode& m : modes_)
        if (m.format_index == format && m.frame_index == frame) mode = &m;
    std::uint32_t best = mode->intervals.front();
    for (std::uint32_t i : mode->intervals)
        if (interval && std::abs(double(i) - interval) < std::abs(double(best) - interval)) best = i;
    return {*mode, best};
}

ControlReply UvcCamera::streaming_request(const SetupPacket& s, std::span<const std::uint8_t> out) {
    const bool probe = (s.value >> 8) == UVC_VS_PROBE_CONTROL;
    std::lock_guard lock(mutex_);
    switch (s.request) {
        case UVC_SET_CUR:
            (probe ? probe_ : commit_) = clamp(out);
            if (!probe) streaming_ = true;  // a commit starts the stream: bulk has no alternate setting to say so
            return done();
        case UVC_GET_CUR: return bytes(streaming_control(probe ? probe_ : commit_));
        case UVC_GET_MIN:
        case UVC_GET_MAX:
        case UVC_GET_DEF: return bytes(streaming_control({probe_.mode, probe_.mode.intervals.front()}));
        case UVC_GET_INFO: return bytes({0x03});
        case UVC_GET_LEN: return u16(kStreamingControlSize);
        default: return ControlReply::refuse();
    }
}

ControlReply UvcCamera::zoom_request(const SetupPacket& s, std::span<const std::uint8_t> out) {
    const ZoomRange& z = spec_.zoom;
    switch (s.request) {
        case UVC_SET_CUR: {
            if (out.size() < 2) return ControlReply::refuse();
            const auto value = std::clamp<std::uint16_t>(std::uint16_t(out[0] | out[1] << 8), z.minimum, z.maximum);
            {
                std::lock_guard lock(mutex_);
                zoom_value_ = value;
            }
            if (on_zoom_) on_zoom_(value);
            return done();
        }
        case UVC_GET_CUR: {
            std::lock_guard lock(mutex_);
            return u16(zoom_value_);
        }
        case UVC_GET_MIN: return u16(z.minimum);
        case UVC_GET_MAX: return u16(z.maximum);
        case UVC_GET_RES: return u16(z.step);
        case UVC_GET_DEF: return u16(z.default_value);
        case UVC_GET_INFO: return bytes({0x03});
        case UVC_GET_LEN: return u16(2);
        default: return ControlReply::refuse();
    }
}

std::optional<Committed> UvcCamera::streaming() const {
    std::lock_guard lock(mutex_);
    if (!streaming_) return std::nullopt;
    return commit_;
}

bool UvcCamera::streams_locked(const Committed& c) const {
    return streaming_ && c.mode.format_index == commit_.mode.format_index &&
           c.mode.frame_index == commit_.mode.frame_index;
}

bool UvcCamera::still_streaming(const Committed& c) const {
    std::lock_guard lock(mutex_);
    return streams_locked(c);
}

// uvcvideo reads a bulk payload across as many transfers as it takes and
// ends it at a short transfer, or once dwMaxPayloadTransferSize bytes came; a
// payload that fills its last transfer exactly and is shorter than that ends
// with an empty transfer (a zero-length packet on a real bus).
bool UvcCamera::send_frame(const Committed& c, std::size_t frame_size, const FrameBytes& frame) {
    std::uint8_t header[2];
    {
        std::lock_guard lock(mutex_);
        if (!streams_locked(c)) return false;
        fid_ ^= 1;
        header[0] = 2;
        header[1] = std::uint8_t(0x80 | 0x02 | fid_);  // EOH, EOF, FID
    }
    const std::size_t total = sizeof header + frame_size;
    std::size_t sent = 0;
    bool ended = false;
    std::vector<std::uint8_t> chunk;
    while (!ended) {
        const std::optional<std::size_t> want = device_->next_in(kStreamingEndpointNumber, kPollS);
        if (!want) {
            if (!device_->plugged() || !still_streaming(c)) return false;
            continue;
        }
        const std::size_t end = std::min(total, sent + *want);
        chunk.clear();
        if (end > sent) {
            const std::uint8_t* pixels = frame(std::max(end, sizeof header) - sizeof header);
            for (std::size_t i = sent; i < std::min(end, sizeof header); ++i) chunk.push_back(header[i]);
            const std::size_t from = std::max(sent, sizeof header) - sizeof header, to = end - sizeof header;
            if (to > from) chunk.insert(chunk.end(), pixels + from, pixels + to);
        }
        const std::optional<std::size_t> length = device_->complete_in(kStreamingEndpointNumber, chunk);
        if (!length) continue;  // cancelled meanwhile: the next one takes the bytes
        const std::size_t took = std::min(chunk.size(), *length);
        ended = sent == total || (sent + took == total && (took < *length || total >= c.mode.max_payload_bytes()));
        sent += took;
    }
    return true;
}

}  // namespace vkfuse::emulator

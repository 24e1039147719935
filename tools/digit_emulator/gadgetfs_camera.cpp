// The emulated DIGIT's GadgetFS device (gadgetfs_camera.hpp). GadgetFS's
// protocol on ep0: write the descriptors once; then read events; a SETUP
// event's data stage is a write (IN) or read (OUT) of the same file, a status
// stage a read of 0 bytes, and a transfer in the wrong direction stalls.
#include "gadgetfs_camera.hpp"

#include <fcntl.h>
#include <linux/usb/ch9.h>
#include <linux/usb/gadgetfs.h>
#include <linux/usb/video.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "vkfuse/core/error.hpp"

namespace vkfuse::emulator {
namespace {

template <class T>
void put(std::vector<std::uint8_t>& out, std::size_t at, T v) {
    for (std::size_t i = 0; i < sizeof(T); ++i) out[at + i] = std::uint8_t(std::uint64_t(v) >> (8 * i));
}

template <class T>
T get(std::span<const std::uint8_t> in, std::size_t at) {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < sizeof(T) && at + i < in.size(); ++i) v |= std::uint64_t(in[at + i]) << (8 * i);
    return T(v);
}

void append(std::vector<std::uint8_t>& out, const std::vector<std::uint8_t>& more) {
    out.insert(out.end(), more.begin(), more.end());
}

constexpr std::size_t kStreamingControlSize = 34;  // UVC 1.1 probe/commit
constexpr int kWakeSignal = SIGWINCH;

}  // namespace

GadgetfsCamera::GadgetfsCamera(const CameraSpec& spec, std::function<void(std::uint16_t)> on_zoom)
    : spec_(spec), on_zoom_(std::move(on_zoom)), zoom_value_(spec.zoom.default_value) {
    const std::string path = spec.gadgetfs + "/" + spec.udc;
    ep0_ = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (ep0_ < 0) throw Error(ErrorKind::Device, path + ": cannot open (gadgetfs mounted?): " + std::strerror(errno));
    std::vector<std::uint8_t> blob(4, 0);  // tag 0: full- and high-speed configurations, then the device
    append(blob, config_descriptor(false));
    append(blob, config_descriptor(true));
    append(blob, device_descriptor(spec.bcd_device));
    if (::write(ep0_, blob.data(), blob.size()) != ssize_t(blob.size())) {
        const int err = errno;
        ::close(ep0_);
        throw Error(ErrorKind::Device, path + ": descriptors refused: " + std::strerror(err));
    }
    probe_ = commit_ = Committed{modes_.front(), modes_.front().intervals.front()};
    // The thread's blocking read is interrupted by kWakeSignal (a handler
    // that does nothing, installed without SA_RESTART) when the camera goes.
    struct sigaction wake {};
    wake.sa_handler = [](int) {};
    ::sigaction(kWakeSignal, &wake, nullptr);
    ep0_thread_ = std::thread([this] { serve(); });
}

GadgetfsCamera::~GadgetfsCamera() {
    unplug();
    configure(false);
}

void GadgetfsCamera::unplug() {
    std::lock_guard lock(unplug_mutex_);
    if (ep0_ < 0) return;
    {
        std::lock_guard state(mutex_);
        streaming_ = false;
    }
    stop_ = true;
    ::pthread_kill(ep0_thread_.native_handle(), kWakeSignal);
    ep0_thread_.join();
    // Closing ep0 unregisters the device: the host sees it go, and a frame
    // write it was never going to read fails, so the endpoint goes idle.
    ::close(ep0_);
    ep0_ = -1;
}

void GadgetfsCamera::serve() {
    while (!stop_) {
        usb_gadgetfs_event events[5];
        const ssize_t n = ::read(ep0_, events, sizeof events);
        if (n < 0) {
            if (errno != EAGAIN && errno != EINTR)
                std::fprintf(stderr, "digit-emulator: ep0: %s\n", std::strerror(errno));
            continue;
        }
        try {
            handle(events, std::size_t(n) / sizeof events[0]);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "digit-emulator: %s\n", e.what());
        }
    }
}

void GadgetfsCamera::handle(const usb_gadgetfs_event* events, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
        switch (events[i].type) {
            case GADGETFS_CONNECT: high_speed_ = events[i].u.speed == USB_SPEED_HIGH; break;
            case GADGETFS_SETUP: on_setup(events[i].u.setup); break;
            case GADGETFS_DISCONNECT: configure(false); break;
            case GADGETFS_SUSPEND: break;
            default: break;
        }
    }
}

void GadgetfsCamera::answer(std::span<const std::uint8_t> data, std::uint16_t length) {
    const std::size_t n = std::min<std::size_t>(data.size(), length);
    if (::write(ep0_, data.data(), n) < 0 && errno != ESHUTDOWN)
        std::fprintf(stderr, "digit-emulator: ep0 answer: %s\n", std::strerror(errno));
}

void GadgetfsCamera::ack() {
    if (::read(ep0_, nullptr, 0) < 0 && errno != ESHUTDOWN)
        std::fprintf(stderr, "digit-emulator: ep0 status: %s\n", std::strerror(errno));
}

void GadgetfsCamera::stall(bool in) {
    // A transfer against the request's direction stalls it.
    if (in) {
        std::uint8_t none = 0;
        (void)::read(ep0_, &none, 0);
    } else {
        (void)::write(ep0_, nullptr, 0);
    }
}

void GadgetfsCamera::configure(bool on) {
    std::unique_lock lock(mutex_);
    streaming_ = false;
    if (ep_in_ >= 0) {
        idle_.wait(lock, [&] { return !writing_; });  // a write in flight fails at a disconnect
        ::close(ep_in_);
        ep_in_ = -1;
    }
    if (!on) return;
    const std::string path = spec_.gadgetfs + "/ep1in-bulk";
    const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) throw Error(ErrorKind::Device, path + ": cannot open: " + std::strerror(errno));
    std::vector<std::uint8_t> blob = {1, 0, 0, 0};  // tag 1: full- then high-speed endpoint descriptor
    append(blob, endpoint_descriptor(false));
    append(blob, endpoint_descriptor(true));
    if (::write(fd, blob.data(), blob.size()) != ssize_t(blob.size())) {
        const int err = errno;
        ::close(fd);
        throw Error(ErrorKind::Device, path + ": endpoint refused: " + std::strerror(err));
    }
    ep_in_ = fd;
}

bool GadgetfsCamera::configured() const {
    std::lock_guard lock(mutex_);
    return ep_in_ >= 0;
}

void GadgetfsCamera::stop_stream() {
    std::lock_guard lock(mutex_);
    streaming_ = false;
}

void GadgetfsCamera::on_setup(const usb_ctrlrequest& req) {
    if (std::getenv("VKFUSE_EMULATOR_TRACE"))
        std::fprintf(stderr, "digit-emulator: setup %02x %02x %04x %04x %u\n", req.bRequestType, req.bRequest, req.wValue,
                     req.wIndex, req.wLength);
    const bool in = req.bRequestType & USB_DIR_IN;
    const unsigned type = req.bRequestType & USB_TYPE_MASK;
    if (type == USB_TYPE_CLASS) return on_class_request(req);
    if (type != USB_TYPE_STANDARD) return stall(in);
    switch (req.bRequest) {
        case USB_REQ_GET_DESCRIPTOR:
            if ((req.wValue >> 8) == USB_DT_STRING && (req.wValue & 0xff) <= 3)
                return answer(string_descriptor(req.wValue & 0xff, spec_.serial), req.wLength);
            return stall(in);
        case USB_REQ_SET_CONFIGURATION:
            configure(req.wValue != 0);
            return ack();
        case USB_REQ_SET_INTERFACE: return ack();
        case USB_REQ_CLEAR_FEATURE:
            // uvcvideo clears the halt of a bulk streaming endpoint when it stops streaming.
            if ((req.bRequestType & USB_RECIP_MASK) == USB_RECIP_ENDPOINT && (req.wIndex & 0xff) == kStreamingEndpoint)
                stop_stream();
            return ack();
        case USB_REQ_GET_STATUS: {
            const std::uint8_t status[2] = {0, 0};
            return answer(status, req.wLength);
        }
        default: return in ? stall(in) : ack();
    }
}

std::vector<std::uint8_t> GadgetfsCamera::streaming_control(const Committed& c) const {
    std::vector<std::uint8_t> out(kStreamingControlSize, 0);
    put<std::uint16_t>(out, 0, 1);  // bmHint: dwFrameInterval fixed
    out[2] = std::uint8_t(c.mode.format_index);
    out[3] = std::uint8_t(c.mode.frame_index);
    put<std::uint32_t>(out, 4, c.interval);
    put<std::uint32_t>(out, 18, c.mode.max_frame_bytes());
    // One payload per frame: its header and the whole frame in one bulk transfer.
    put<std::uint32_t>(out, 22, c.mode.max_frame_bytes() + 2);
    put<std::uint32_t>(out, 26, 48000000);
    out[30] = 3;  // bmFramingInfo: FID and EOF are used
    out[31] = out[32] = out[33] = 1;
    return out;
}

Committed GadgetfsCamera::clamp(std::span<const std::uint8_t> probe) const {
    const int format = probe.size() > 2 ? probe[2] : 0, frame = probe.size() > 3 ? probe[3] : 0;
    const std::uint32_t interval = get<std::uint32_t>(probe, 4);
    const StreamMode* mode = &modes_.front();
    for (const StreamMode& m : modes_)
        if (m.format_index == format && m.frame_index == frame) mode = &m;
    std::uint32_t best = mode->intervals.front();
    for (std::uint32_t i : mode->intervals)
        if (interval && std::abs(double(i) - interval) < std::abs(double(best) - interval)) best = i;
    return {*mode, best};
}

void GadgetfsCamera::on_class_request(const usb_ctrlrequest& req) {
    const bool in = req.bRequestType & USB_DIR_IN;
    const int interface = req.wIndex & 0xff, entity = req.wIndex >> 8, selector = req.wValue >> 8;
    const auto u16 = [](unsigned v) { return std::vector<std::uint8_t>{std::uint8_t(v), std::uint8_t(v >> 8)}; };
    if (interface == kStreamingInterface && (selector == UVC_VS_PROBE_CONTROL || selector == UVC_VS_COMMIT_CONTROL)) {
        const bool probe = selector == UVC_VS_PROBE_CONTROL;
        switch (req.bRequest) {
            case UVC_SET_CUR: {
                std::vector<std::uint8_t> data(req.wLength);
                const ssize_t n = ::read(ep0_, data.data(), data.size());
                if (n < 0) return;
                data.resize(std::size_t(n));
                (probe ? probe_ : commit_) = clamp(data);
                if (!probe) {  // a commit starts the stream: bulk has no alternate setting to say so
                    std::lock_guard lock(mutex_);
                    streaming_ = true;
                }
                return;
            }
            case UVC_GET_CUR: return answer(streaming_control(probe ? probe_ : commit_), req.wLength);
            case UVC_GET_MIN:
            case UVC_GET_MAX:
            case UVC_GET_DEF: return answer(streaming_control({probe_.mode, probe_.mode.intervals.front()}), req.wLength);
            case UVC_GET_INFO: return answer(std::vector<std::uint8_t>{0x03}, req.wLength);
            case UVC_GET_LEN: return answer(u16(kStreamingControlSize), req.wLength);
            default: return stall(in);
        }
    }
    if (interface == kControlInterface && entity == kCameraTerminalId && selector == UVC_CT_ZOOM_ABSOLUTE_CONTROL) {
        const ZoomRange& z = spec_.zoom;
        switch (req.bRequest) {
            case UVC_SET_CUR: {
                std::uint8_t data[2] = {0, 0};
                if (::read(ep0_, data, std::min<std::size_t>(req.wLength, 2)) < 0) return;
                zoom_value_ = std::clamp<std::uint16_t>(std::uint16_t(data[0] | (data[1] << 8)), z.minimum, z.maximum);
                if (on_zoom_) on_zoom_(zoom_value_);
                return;
            }
            case UVC_GET_CUR: return answer(u16(zoom_value_), req.wLength);
            case UVC_GET_MIN: return answer(u16(z.minimum), req.wLength);
            case UVC_GET_MAX: return answer(u16(z.maximum), req.wLength);
            case UVC_GET_RES: return answer(u16(z.step), req.wLength);
            case UVC_GET_DEF: return answer(u16(z.default_value), req.wLength);
            case UVC_GET_INFO: return answer(std::vector<std::uint8_t>{0x03}, req.wLength);
            case UVC_GET_LEN: return answer(u16(2), req.wLength);
            default: return stall(in);
        }
    }
    if (interface == kControlInterface && entity == 0 && selector == UVC_VC_REQUEST_ERROR_CODE_CONTROL && in) {
        if (req.bRequest == UVC_GET_CUR) return answer(std::vector<std::uint8_t>{0x06}, req.wLength);  // invalid control
        if (req.bRequest == UVC_GET_INFO) return answer(std::vector<std::uint8_t>{0x01}, req.wLength);
    }
    stall(in);
}

std::optional<Committed> GadgetfsCamera::streaming() const {
    std::lock_guard lock(mutex_);
    if (!streaming_ || ep_in_ < 0) return std::nullopt;
    return commit_;
}

bool GadgetfsCamera::submit(const Committed& c, std::span<const std::uint8_t> frame) {
    int fd;
    std::vector<std::uint8_t> payload;
    {
        std::lock_guard lock(mutex_);
        if (!streaming_ || ep_in_ < 0 || c.mode.format_index != commit_.mode.format_index ||
            c.mode.frame_index != commit_.mode.frame_index)
            return false;
        fd = ep_in_;
        writing_ = true;
        fid_ ^= 1;
        payload = {2, std::uint8_t(0x80 | 0x02 | fid_)};  // header: EOH, EOF, FID
    }
    payload.insert(payload.end(), frame.begin(), frame.end());
    // A payload that ends on a packet boundary would not end the host's
    // transfer: one byte more (after a JPEG's end marker, ignored).
    if (payload.size() % 512 == 0 && payload.size() < c.mode.max_frame_bytes() + 2) payload.push_back(0);
    const bool ok = ::write(fd, payload.data(), payload.size()) == ssize_t(payload.size());
    {
        std::lock_guard lock(mutex_);
        writing_ = false;
    }
    idle_.notify_all();
    return ok;
}

}  // namespace vkfuse::emulator

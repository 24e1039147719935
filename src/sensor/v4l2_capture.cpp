// V4L2 mmap streaming (v4l2_capture.hpp). The kernel's buffer queue holds
// every mapped buffer but the one lent out, so the camera never stalls while
// a frame is decoded.
#include "v4l2_capture.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>

#include "vkfuse/core/error.hpp"

namespace vkfuse::v4l2 {
namespace {

int xioctl(int fd, unsigned long request, void* arg) {
    int r;
    do r = ::ioctl(fd, request, arg);
    while (r < 0 && errno == EINTR);
    return r;
}

// What a request to a camera that is being unplugged fails with: the node
// gone (ENODEV, ENXIO), or a USB transfer the host controller cut short as
// the device went (uvcvideo passes ESHUTDOWN, EPROTO and EIO through).
bool gone(int err) { return err == ENODEV || err == ENXIO || err == EIO || err == ESHUTDOWN || err == EPROTO; }

double seconds(const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; }

}  // namespace

std::string fourcc_text(std::uint32_t f) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        const char c = char((f >> (8 * i)) & 0xff);
        s += c >= 32 && c < 127 ? c : '?';
    }
    return s;
}

double monotonic_now() {
    timespec t{};
    ::clock_gettime(CLOCK_MONOTONIC, &t);
    return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

void Capture::fail(const std::string& what, int err) const {
    const std::string message = subject_ + ": " + what + ": " + std::strerror(err);
    throw Error(gone(err) ? ErrorKind::Unplugged : ErrorKind::Device, gone(err) ? subject_ + ": unplugged (" + what + ")" : message);
}

Capture::Capture(const std::string& node, std::string subject) : subject_(std::move(subject)) {
    fd_ = ::open(node.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) {
        const int err = errno;
        throw Error(err == ENOENT ? ErrorKind::Unplugged : ErrorKind::Device,
                    subject_ + ": cannot open " + node + ": " + std::strerror(err));
    }
    v4l2_capability cap{};
    if (xioctl(fd_, VIDIOC_QUERYCAP, &cap) < 0) {
        const int err = errno;
        ::close(fd_);
        fd_ = -1;
        throw Error(ErrorKind::Device, subject_ + ": " + node + " is not a V4L2 device: " + std::strerror(err));
    }
    const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if (!(caps & V4L2_CAP_VIDEO_CAPTURE) || !(caps & V4L2_CAP_STREAMING)) {
        ::close(fd_);
        fd_ = -1;
        throw Error(ErrorKind::Device, subject_ + ": " + node + " is not a streaming video capture node");
    }
}

Capture::~Capture() {
    stop();
    if (fd_ >= 0) ::close(fd_);
}

void Capture::stop() noexcept {
    if (streaming_) {
        int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        xioctl(fd_, VIDIOC_STREAMOFF, &type);
        streaming_ = false;
    }
    for (const Mapping& m : mappings_) ::munmap(m.data, m.length);
    mappings_.clear();
}

std::vector<Mode> Capture::modes() const {
    std::vector<Mode> out;
    for (std::uint32_t f = 0;; ++f) {
        v4l2_fmtdesc desc{};
        desc.index = f;
        desc.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (xioctl(fd_, VIDIOC_ENUM_FMT, &desc) < 0) break;
        for (std::uint32_t s = 0;; ++s) {
            v4l2_frmsizeenum size{};
            size.index = s;
            size.pixel_format = desc.pixelformat;
            if (xioctl(fd_, VIDIOC_ENUM_FRAMESIZES, &size) < 0 || size.type != V4L2_FRMSIZE_TYPE_DISCRETE) break;
            for (std::uint32_t i = 0;; ++i) {
                v4l2_frmivalenum ival{};
                ival.index = i;
                ival.pixel_format = desc.pixelformat;
                ival.width = size.discrete.width;
                ival.height = size.discrete.height;
                if (xioctl(fd_, VIDIOC_ENUM_FRAMEINTERVALS, &ival) < 0 || ival.type != V4L2_FRMIVAL_TYPE_DISCRETE ||
                    ival.discrete.numerator == 0)
                    break;
                out.push_back({desc.pixelformat, int(size.discrete.width), int(size.discrete.height),
                               double(ival.discrete.denominator) / double(ival.discrete.numerator)});
            }
        }
    }
    return out;
}

void Capture::configure(const Mode& mode) {
    v4l2_format fmt{};
    fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    fmt.fmt.pix.width = std::uint32_t(mode.width);
    fmt.fmt.pix.height = std::uint32_t(mode.height);
    fmt.fmt.pix.pixelformat = mode.fourcc;
    fmt.fmt.pix.field = V4L2_FIELD_NONE;
    if (xioctl(fd_, VIDIOC_S_FMT, &fmt) < 0) fail("setting the format", errno);
    const std::string wanted =
        fourcc_text(mode.fourcc) + " " + std::to_string(mode.width) + "x" + std::to_string(mode.height);
    if (fmt.fmt.pix.pixelformat != mode.fourcc || int(fmt.fmt.pix.width) != mode.width ||
        int(fmt.fmt.pix.height) != mode.height)
        throw Error(ErrorKind::Device, subject_ + ": does not stream " + wanted + " (the driver chose " +
                                           fourcc_text(fmt.fmt.pix.pixelformat) + " " +
                                           std::to_string(fmt.fmt.pix.width) + "x" +
                                           std::to_string(fmt.fmt.pix.height) + ")");
    v4l2_streamparm parm{};
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    parm.parm.capture.timeperframe.numerator = 1000;
    parm.parm.capture.timeperframe.denominator = std::uint32_t(std::lround(mode.fps * 1000));
    if (xioctl(fd_, VIDIOC_S_PARM, &parm) < 0) fail("setting the frame rate", errno);
    const v4l2_fract got = parm.parm.capture.timeperframe;
    if (got.numerator == 0 || std::abs(double(got.denominator) / got.numerator - mode.fps) > 0.01 * mode.fps)
        throw Error(ErrorKind::Device, subject_ + ": does not stream " + wanted + " at " +
                                           std::to_string(int(std::lround(mode.fps))) + " fps");
}

void Capture::start(int buffers) {
    v4l2_requestbuffers req{};
    req.count = std::uint32_t(buffers);
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    if (xioctl(fd_, VIDIOC_REQBUFS, &req) < 0) fail("allocating buffers", errno);
    if (req.count < 2) throw Error(ErrorKind::Device, subject_ + ": the driver gave fewer than 2 buffers");
    for (std::uint32_t i = 0; i < req.count; ++i) {
        v4l2_buffer buf{};
        buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        buf.memory = V4L2_MEMORY_MMAP;
        buf.index = i;
        if (xioctl(fd_, VIDIOC_QUERYBUF, &buf) < 0) fail("querying a buffer", errno);
        void* p = ::mmap(nullptr, buf.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, buf.m.offset);
        if (p == MAP_FAILED) fail("mapping a buffer", errno);
        mappings_.push_back({p, buf.length});
        requeue(int(i));
    }
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd_, VIDIOC_STREAMON, &type) < 0) fail("starting the stream", errno);
    streaming_ = true;
}

std::optional<Filled> Capture::dequeue(double timeout_s) {
    const double deadline = monotonic_now() + timeout_s;
    for (;;) {
        v4l2_buffer buf{};
        buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        buf.memory = V4L2_MEMORY_MMAP;
        if (xioctl(fd_, VIDIOC_DQBUF, &buf) == 0) {
            if (buf.index >= mappings_.size() || buf.bytesused > mappings_[buf.index].length)
                throw Error(ErrorKind::Device, subject_ + ": the driver returned a buffer out of range");
            Filled f;
            f.index = int(buf.index);
            f.bytes = {static_cast<const std::uint8_t*>(mappings_[buf.index].data), buf.bytesused};
            f.driver_timestamp = (buf.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC &&
                                 (buf.timestamp.tv_sec != 0 || buf.timestamp.tv_usec != 0);
            f.timestamp = f.driver_timestamp ? seconds(buf.timestamp) : monotonic_now();
            f.error = (buf.flags & V4L2_BUF_FLAG_ERROR) != 0;
            f.sequence = buf.sequence;
            return f;
        }
        if (errno != EAGAIN) fail("dequeuing a frame", errno);
        const double left = deadline - monotonic_now();
        if (left <= 0) return std::nullopt;
        pollfd p{fd_, POLLIN, 0};
        const int r = ::poll(&p, 1, int(std::ceil(left * 1000)));
        if (r < 0 && errno != EINTR) fail("waiting for a frame", errno);
        if (r > 0 && (p.revents & (POLLERR | POLLHUP | POLLNVAL)) && !(p.revents & POLLIN))
            throw Error(ErrorKind::Unplugged, subject_ + ": unplugged (the stream stopped)");
    }
}

void Capture::requeue(int index) {
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    buf.index = std::uint32_t(index);
    if (xioctl(fd_, VIDIOC_QBUF, &buf) < 0) fail("queuing a buffer", errno);
}

std::optional<ControlInfo> Capture::query_control(std::uint32_t id) const {
    v4l2_queryctrl q{};
    q.id = id;
    if (xioctl(fd_, VIDIOC_QUERYCTRL, &q) < 0 || (q.flags & V4L2_CTRL_FLAG_DISABLED)) return std::nullopt;
    return ControlInfo{q.minimum, q.maximum, q.step, q.default_value, q.type};
}

void Capture::set_control(std::uint32_t id, std::int32_t value) {
    v4l2_control c{id, value};
    if (xioctl(fd_, VIDIOC_S_CTRL, &c) < 0) fail("setting control " + std::to_string(id), errno);
}

std::int32_t Capture::get_control(std::uint32_t id) const {
    v4l2_control c{id, 0};
    if (xioctl(fd_, VIDIOC_G_CTRL, &c) < 0) fail("reading control " + std::to_string(id), errno);
    return c.value;
}

}  // namespace vkfuse::v4l2

// The device end of a USB/IP link (usbip_device.hpp). The wire format is the
// kernel's (Documentation/usb/usbip_protocol.rst): every message starts with
// a 48-byte header of big-endian 32-bit words; an OUT transfer's data follows
// its CMD_SUBMIT, an IN transfer's data its RET_SUBMIT.
#include "usbip_device.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "vkfuse/core/error.hpp"

namespace vkfuse::emulator {
namespace {

constexpr std::uint32_t kCmdSubmit = 1, kCmdUnlink = 2, kRetSubmit = 3, kRetUnlink = 4;
constexpr std::size_t kHeaderBytes = 48;
constexpr std::uint32_t kUsbSpeedHigh = 3;    // enum usb_device_speed
constexpr std::uint32_t kPortFree = 4;        // VDEV_ST_NULL in vhci's status
constexpr std::size_t kMaxTransfer = 1 << 24;  // larger than any transfer a UVC host makes
constexpr std::int32_t kStall = -EPIPE, kUnlinked = -ECONNRESET;

using Header = std::array<std::uint8_t, kHeaderBytes>;

std::uint32_t word(const Header& h, std::size_t at) {
    return std::uint32_t(h[at]) << 24 | std::uint32_t(h[at + 1]) << 16 | std::uint32_t(h[at + 2]) << 8 | h[at + 3];
}
void put_word(Header& h, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) h[at + std::size_t(i)] = std::uint8_t(v >> (24 - 8 * i));
}

bool read_all(int fd, std::uint8_t* p, std::size_t n) {
    while (n > 0) {
        const ssize_t got = ::read(fd, p, n);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        p += got;
        n -= std::size_t(got);
    }
    return true;
}
bool write_all(int fd, const std::uint8_t* p, std::size_t n) {
    while (n > 0) {
        const ssize_t put = ::send(fd, p, n, MSG_NOSIGNAL);
        if (put < 0 && errno == EINTR) continue;
        if (put <= 0) return false;
        p += put;
        n -= std::size_t(put);
    }
    return true;
}

// The USB device usbcore made for high-speed port `port` of vhci
// ("<vhci>/usbN/N-<port + 1>", on the bus whose speed is 480 Mb/s): there
// until usbcore has removed it, which it does only once every transfer of it
// has been given back.
bool port_device_exists(const std::string& vhci, int port) {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (const fs::directory_entry& bus : fs::directory_iterator(vhci, ec)) {
        const std::string name = bus.path().filename().string();
        if (name.rfind("usb", 0) != 0) continue;
        std::ifstream speed(bus.path() / "speed");
        int mbps = 0;
        if (!(speed >> mbps) || mbps != 480) continue;
        return fs::exists(bus.path() / (name.substr(3) + "-" + std::to_string(port + 1)), ec);
    }
    return false;
}

// vhci's status lists its ports, one per line: "hs  0003 004 000 00000000 ...":
// hub, port, state, speed, device id, ... The high-speed ports free for a new
// device: vhci marks a port free (state 4) as soon as it has shut the old
// connection down, before usbcore has removed the old device and cancelled
// its transfers; a device attached in between would get the old device's
// cancellations and leftover submits on its own link (they belong to no
// transfer it knows, and usbcore waits for their answers for ever). So a
// port counts as free only once its old device is gone too.
std::vector<int> free_high_speed_ports(const std::string& vhci) {
    std::ifstream status(vhci + "/status");
    if (!status) throw Error(ErrorKind::Device, vhci + "/status: cannot read (is vhci_hcd loaded?)");
    std::vector<int> out;
    std::string line;
    while (std::getline(status, line)) {
        std::istringstream fields(line);
        std::string hub;
        int port = -1;
        unsigned state = 0;
        if (fields >> hub >> port >> state && hub == "hs" && state == kPortFree && !port_device_exists(vhci, port))
            out.push_back(port);
    }
    return out;
}

bool port_free(const std::string& vhci, int port) {
    const std::vector<int> free = free_high_speed_ports(vhci);
    return std::find(free.begin(), free.end(), port) != free.end();
}

}  // namespace

UsbipDevice::Link UsbipDevice::attach(const std::string& vhci) {
    int pair[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0)
        throw Error(ErrorKind::Device, std::string("socketpair: ") + std::strerror(errno));
    // The kernel looks the socket up by its number in this process, and keeps
    // it; another program attaching at the same moment may take the port first.
    std::string refused = "no free high-speed port";
    int attached = -1;
    for (int port : free_high_speed_ports(vhci)) {
        std::ofstream request(vhci + "/attach");
        request << port << ' ' << pair[1] << ' ' << ((1u << 16) | unsigned(port + 1)) << ' ' << kUsbSpeedHigh;
        request.flush();
        if (request) {
            attached = port;
            break;
        }
        refused = "port " + std::to_string(port) + " refused the device";
    }
    ::close(pair[1]);
    if (attached < 0) {
        ::close(pair[0]);
        throw Error(ErrorKind::Device, vhci + "/attach: " + refused);
    }
    return {pair[0], attached};
}

UsbipDevice::UsbipDevice(ControlHandler on_control, std::string vhci)
    : UsbipDevice(std::move(on_control), attach(vhci)) {
    vhci_ = std::move(vhci);
}

UsbipDevice::UsbipDevice(ControlHandler on_control, int link_fd)
    : UsbipDevice(std::move(on_control), Link{link_fd, -1}) {}

UsbipDevice::UsbipDevice(ControlHandler on_control, Link link)
    : on_control_(std::move(on_control)),
      trace_(std::getenv("VKFUSE_USBIP_TRACE") != nullptr),
      fd_(link.fd),
      port_(link.port) {
    up_ = true;
    thread_ = std::thread([this] { serve(); });
}

UsbipDevice::~UsbipDevice() { unplug(); }

void UsbipDevice::unplug() {
    std::lock_guard once(unplug_mutex_);
    if (fd_ < 0) return;
    ::shutdown(fd_, SHUT_RDWR);  // the reader sees the end of the stream, vhci the device go
    thread_.join();
    ::close(fd_);
    fd_ = -1;
    // Unplugged is when the host is done with the device: its port free and
    // usbcore's device removed (seconds under emulation on a loaded host), so
    // that whoever plugs next finds a clean port. Bounded: a host that never
    // lets go is reported, not waited for.
    if (port_ < 0) return;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!port_free(vhci_, port_)) {
        if (std::chrono::steady_clock::now() > deadline) {
            std::fprintf(stderr, "digit-emulator: port %d of %s still busy 60 s after the unplug\n", port_,
                         vhci_.c_str());
            return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

bool UsbipDevice::plugged() const {
    std::lock_guard lock(mutex_);
    return up_;
}

void UsbipDevice::serve() {
    while (serve_one()) {
    }
    std::lock_guard lock(mutex_);
    up_ = false;
    pending_.clear();
    arrived_.notify_all();
}

bool UsbipDevice::serve_one() {
    Header h{};
    if (!read_all(fd_, h.data(), h.size())) return false;
    const std::uint32_t command = word(h, 0), seqnum = word(h, 4), direction_in = word(h, 12), ep = word(h, 16);
    if (command == kCmdUnlink) {
        const std::uint32_t victim = word(h, 20);
        std::lock_guard lock(mutex_);
        if (!any_submit_) {
            // Nothing submitted on this link yet: the transfer is not this
            // link's to hold (one of a device vhci had on the port before).
            // Answered as cancelled, so its owner is not left waiting; should
            // its submit come after all, it is dropped unanswered.
            answered_unlinks_.insert(victim);
            send(kRetUnlink, seqnum, kUnlinked, {}, 0);
            if (trace_) std::fprintf(stderr, "usbip: unlink %u of %u before any submit: %d\n", seqnum, victim, kUnlinked);
            return true;
        }
        if (std::int32_t(victim - last_submit_) > 0) {
            // Not submitted yet: vhci sends the unlinks it has queued after
            // the submits, so a transfer submitted and cancelled between two
            // of its passes has its unlink come first. Answered as a
            // cancellation once the submit arrives, and the submit never
            // completed: a status 0 now would have vhci give the transfer
            // back, and its RET_SUBMIT later would find none and drop the device.
            early_unlinks_[victim] = seqnum;
            if (trace_) std::fprintf(stderr, "usbip: unlink %u of %u before its submit\n", seqnum, victim);
            return true;
        }
        // Still pending: it is cancelled here and never completed. Already
        // completed: the host has (or will have) its RET_SUBMIT.
        std::int32_t status = 0;
        for (auto& [number, queue] : pending_) {
            const auto it = std::find_if(queue.begin(), queue.end(), [&](const Pending& p) { return p.seqnum == victim; });
            if (it != queue.end()) {
                queue.erase(it);
                status = kUnlinked;
            }
        }
        send(kRetUnlink, seqnum, status, {}, 0);
        if (trace_) std::fprintf(stderr, "usbip: unlink %u of %u: %d\n", seqnum, victim, status);
        return true;
    }
    if (command != kCmdSubmit) {
        std::fprintf(stderr, "digit-emulator: usbip: unknown command %u; closing the link\n", command);
        return false;
    }
    const std::size_t length = word(h, 24);
    if (length > kMaxTransfer) {
        std::fprintf(stderr, "digit-emulator: usbip: a %zu-byte transfer; closing the link\n", length);
        return false;
    }
    std::vector<std::uint8_t> out_data;
    if (!direction_in && length > 0) {
        out_data.resize(length);
        if (!read_all(fd_, out_data.data(), length)) return false;
    }
    {
        std::lock_guard lock(mutex_);
        last_submit_ = seqnum;
        any_submit_ = true;
        if (answered_unlinks_.erase(seqnum) > 0) return true;  // the host already has it back
        if (const auto it = early_unlinks_.find(seqnum); it != early_unlinks_.end()) {
            send(kRetUnlink, it->second, kUnlinked, {}, 0);
            if (trace_) std::fprintf(stderr, "usbip: unlink %u of %u: %d\n", it->second, seqnum, kUnlinked);
            early_unlinks_.erase(it);
            return true;
        }
        // vhci sends a port's submits in the order of their numbers: a held
        // unlink of an earlier number waits for a submit that never comes.
        for (auto it = early_unlinks_.begin(); it != early_unlinks_.end();) {
            if (std::int32_t(it->first - seqnum) >= 0) {
                ++it;
                continue;
            }
            send(kRetUnlink, it->second, kUnlinked, {}, 0);
            if (trace_) std::fprintf(stderr, "usbip: unlink %u of %u, passed by %u: %d\n", it->second, it->first, seqnum, kUnlinked);
            it = early_unlinks_.erase(it);
        }
    }
    if (ep == 0) {
        SetupPacket s;
        s.request_type = h[40];
        s.request = h[41];
        s.value = std::uint16_t(h[42] | h[43] << 8);
        s.index = std::uint16_t(h[44] | h[45] << 8);
        s.length = std::uint16_t(h[46] | h[47] << 8);
        const ControlReply r = on_control_(s, out_data);
        std::lock_guard lock(mutex_);
        if (r.stall) send(kRetSubmit, seqnum, kStall, {}, 0);
        else if (direction_in) send(kRetSubmit, seqnum, 0, r.data, std::min<std::size_t>(r.data.size(), length));
        else send(kRetSubmit, seqnum, 0, {}, length);
        return true;
    }
    std::lock_guard lock(mutex_);
    if (!direction_in) {
        send(kRetSubmit, seqnum, kStall, {}, 0);  // no OUT endpoint besides ep0
        return true;
    }
    pending_[ep].push_back({seqnum, length});
    if (trace_) std::fprintf(stderr, "usbip: submit %u ep %u %zu\n", seqnum, ep, length);
    arrived_.notify_all();
    return true;
}

// Writes one reply; the caller holds mutex_, so replies never interleave.
void UsbipDevice::send(std::uint32_t command, std::uint32_t seqnum, std::int32_t status,
                       std::span<const std::uint8_t> data, std::size_t actual) {
    Header h{};
    put_word(h, 0, command);
    put_word(h, 4, seqnum);
    put_word(h, 20, std::uint32_t(status));
    if (command == kRetSubmit) put_word(h, 24, std::uint32_t(actual));
    std::vector<std::uint8_t> message(h.begin(), h.end());
    const std::size_t payload = std::min(actual, data.size());
    message.insert(message.end(), data.begin(), data.begin() + std::ptrdiff_t(payload));
    if (!write_all(fd_, message.data(), message.size())) up_ = false;
}

std::optional<std::size_t> UsbipDevice::next_in(unsigned ep, double timeout_s) {
    std::unique_lock lock(mutex_);
    const bool any = arrived_.wait_for(lock, std::chrono::duration<double>(timeout_s), [&] {
        return !up_ || !pending_[ep].empty();
    });
    if (!any || !up_) return std::nullopt;
    return pending_[ep].front().length;
}

std::optional<std::size_t> UsbipDevice::complete_in(unsigned ep, std::span<const std::uint8_t> data) {
    std::lock_guard lock(mutex_);
    auto& queue = pending_[ep];
    if (!up_ || queue.empty()) return std::nullopt;
    const Pending p = queue.front();
    queue.pop_front();
    send(kRetSubmit, p.seqnum, 0, data, std::min(data.size(), p.length));
    if (trace_) std::fprintf(stderr, "usbip: ret %u %zu\n", p.seqnum, std::min(data.size(), p.length));
    return p.length;
}

}  // namespace vkfuse::emulator

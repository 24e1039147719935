// usbip_device.hpp - the device end of a USB/IP link, in user space: the
// kernel's virtual host controller (vhci_hcd) takes one end of a socket pair
// as a device plugged into one of its ports, and from then on sends every
// transfer the host's drivers make to that device down the socket. This end
// answers them: control transfers at once, through a handler; IN transfers on
// other endpoints when the owner has data for them.
//
//   uvcvideo -> usbcore -> vhci_hcd --CMD_SUBMIT/CMD_UNLINK--> socket --> UsbipDevice
//            <-          <-         <--RET_SUBMIT/RET_UNLINK--        <--
//
// The host waits for each control transfer's answer, status stage included,
// so requests never overtake one another. Unplugging closes the socket: the
// virtual controller sees the device go, as if its cable were pulled.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace vkfuse::emulator {

// A control request's setup packet (USB 2.0, 9.3).
struct SetupPacket {
    std::uint8_t request_type = 0, request = 0;
    std::uint16_t value = 0, index = 0, length = 0;
    bool in() const { return request_type & 0x80; }
};

// A control request's outcome: refused (the endpoint stalls), or accepted
// with the data of an IN request's data stage (cut to wLength when sent).
struct ControlReply {
    bool stall = false;
    std::vector<std::uint8_t> data;
    static ControlReply refuse() { return {true, {}}; }
};

// Answers one control request; out_data is an OUT request's data stage.
using ControlHandler = std::function<ControlReply(const SetupPacket&, std::span<const std::uint8_t> out_data)>;

class UsbipDevice {
public:
    // Plugs the device into the first free high-speed port of `vhci` (its
    // sysfs directory; free: vhci has let the port go and usbcore has removed
    // the device it had) and serves it on a thread of its own; on_control
    // runs there.
    explicit UsbipDevice(ControlHandler on_control, std::string vhci = "/sys/devices/platform/vhci_hcd.0");
    // Serves a link already connected, taking link_fd: the other end of a
    // socket pair, which plays vhci (tests). port() is -1.
    UsbipDevice(ControlHandler on_control, int link_fd);
    ~UsbipDevice();
    UsbipDevice(const UsbipDevice&) = delete;
    UsbipDevice& operator=(const UsbipDevice&) = delete;

    // The length of the oldest IN transfer the host has pending on endpoint
    // `ep` (its number), waiting up to timeout_s for one; nullopt when none
    // came or the device is gone.
    std::optional<std::size_t> next_in(unsigned ep, double timeout_s);
    // Completes that transfer with `data` (cut to its length); returns the
    // transfer's length, or nullopt when none is pending any more (the host
    // cancelled it) or the device is gone.
    std::optional<std::size_t> complete_in(unsigned ep, std::span<const std::uint8_t> data);
    bool plugged() const;
    int port() const { return port_; }
    // Pulls the cable: closes the link; the host sees the device go. On vhci,
    // returns once the host is done with it (its port free, usbcore's device
    // removed; at most a minute), so that a device plugged next finds a
    // clean port.
    void unplug();

private:
    struct Pending {
        std::uint32_t seqnum;
        std::size_t length;
    };
    struct Link {
        int fd, port;
    };
    static Link attach(const std::string& vhci);
    UsbipDevice(ControlHandler on_control, Link link);
    void serve();
    bool serve_one();
    void send(std::uint32_t command, std::uint32_t seqnum, std::int32_t status, std::span<const std::uint8_t> data,
              std::size_t actual);

    ControlHandler on_control_;
    bool trace_;  // VKFUSE_USBIP_TRACE set: every bulk transfer and cancellation on stderr
    int fd_ = -1;
    int port_ = -1;
    std::string vhci_;  // its sysfs directory; empty for a link the caller connected

    mutable std::mutex mutex_;  // everything below; held while a reply is written
    std::condition_variable arrived_;
    std::map<unsigned, std::deque<Pending>> pending_;  // per IN endpoint, oldest first
    std::uint32_t last_submit_ = 0;                    // the newest CMD_SUBMIT's seqnum
    bool any_submit_ = false;                          // a CMD_SUBMIT came on this link
    // Transfers cancelled before this link saw any submit, answered at once;
    // a submit of one of them is dropped.
    std::set<std::uint32_t> answered_unlinks_;
    // CMD_UNLINKs that came before the submit they cancel: its seqnum -> theirs.
    std::map<std::uint32_t, std::uint32_t> early_unlinks_;
    bool up_ = false;

    std::mutex unplug_mutex_;
    std::thread thread_;
};

}  // namespace vkfuse::emulator

// The emulated DIGIT's USB/IP link (tests/hil/digit_emulator/usbip_device.hpp)
// against a scripted host: this test plays vhci_hcd on the other end of a
// socket pair and checks the replies word by word, above all the cancellation
// rules vhci depends on: a transfer it gave back must never be answered
// again, or it drops the device.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "usbip_device.hpp"

namespace vkfuse::test {
namespace {

using emulator::ControlReply;
using emulator::SetupPacket;
using emulator::UsbipDevice;

constexpr std::uint32_t kCmdSubmit = 1, kCmdUnlink = 2, kRetSubmit = 3, kRetUnlink = 4;
constexpr std::uint32_t kDirIn = 1, kBulkEp = 1;

using Header = std::array<std::uint8_t, 48>;

void put(Header& h, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) h[at + std::size_t(i)] = std::uint8_t(v >> (24 - 8 * i));
}
std::uint32_t get(const Header& h, std::size_t at) {
    return std::uint32_t(h[at]) << 24 | std::uint32_t(h[at + 1]) << 16 | std::uint32_t(h[at + 2]) << 8 | h[at + 3];
}

// The host end: writes commands, reads replies (5 s at most per read).
class Host {
public:
    Host() {
        int pair[2];
        if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0) throw std::runtime_error("socketpair");
        fd_ = pair[0];
        device_fd_ = pair[1];
        const timeval limit{5, 0};
        ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
    }
    ~Host() { ::close(fd_); }
    int device_end() const { return device_fd_; }

    void submit_in(std::uint32_t seqnum, std::uint32_t length) {
        Header h{};
        put(h, 0, kCmdSubmit);
        put(h, 4, seqnum);
        put(h, 12, kDirIn);
        put(h, 16, kBulkEp);
        put(h, 24, length);
        write(h);
    }
    void unlink(std::uint32_t seqnum, std::uint32_t victim) {
        Header h{};
        put(h, 0, kCmdUnlink);
        put(h, 4, seqnum);
        put(h, 20, victim);
        write(h);
    }
    struct Reply {
        std::uint32_t command, seqnum;
        std::int32_t status;
        std::vector<std::uint8_t> data;
    };
    // The next reply; an IN RET_SUBMIT's `actual` bytes of data with it.
    Reply next() {
        Header h{};
        read(h.data(), h.size());
        Reply r{get(h, 0), get(h, 4), std::int32_t(get(h, 20)), {}};
        if (r.command == kRetSubmit) {
            r.data.resize(get(h, 24));
            read(r.data.data(), r.data.size());
        }
        return r;
    }

private:
    int fd_ = -1, device_fd_ = -1;
    void write(const Header& h) { ASSERT_EQ(::write(fd_, h.data(), h.size()), ssize_t(h.size())); }
    void read(std::uint8_t* p, std::size_t n) {
        while (n > 0) {
            const ssize_t got = ::read(fd_, p, n);
            if (got <= 0) throw std::runtime_error("no reply from the device within 5 s");
            p += got;
            n -= std::size_t(got);
        }
    }
};

ControlReply no_control(const SetupPacket&, std::span<const std::uint8_t>) { return ControlReply::refuse(); }

// Transfer `seqnum` (8 bytes in) submitted, completed and its RET_SUBMIT read.
void submit_and_complete(Host& host, UsbipDevice& device, std::uint32_t seqnum) {
    host.submit_in(seqnum, 8);
    ASSERT_TRUE(device.next_in(kBulkEp, 5.0));
    ASSERT_TRUE(device.complete_in(kBulkEp, std::vector<std::uint8_t>(8)));
    const Host::Reply r = host.next();
    ASSERT_EQ(r.command, kRetSubmit);
    ASSERT_EQ(r.seqnum, seqnum);
}

TEST(UsbipLink, ATransferIsCompletedWithTheDataGiven) {
    Host host;
    UsbipDevice device(no_control, host.device_end());
    host.submit_in(1, 4);
    ASSERT_EQ(device.next_in(kBulkEp, 5.0), std::optional<std::size_t>(4));
    const std::vector<std::uint8_t> data{1, 2, 3, 4, 5, 6};
    EXPECT_EQ(device.complete_in(kBulkEp, data), std::optional<std::size_t>(4));
    const Host::Reply r = host.next();
    EXPECT_EQ(r.command, kRetSubmit);
    EXPECT_EQ(r.seqnum, 1u);
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.data, (std::vector<std::uint8_t>{1, 2, 3, 4}));  // cut to the transfer's length
}

TEST(UsbipLink, UnlinkingAPendingTransferCancelsIt) {
    Host host;
    UsbipDevice device(no_control, host.device_end());
    host.submit_in(1, 16);
    ASSERT_TRUE(device.next_in(kBulkEp, 5.0));
    host.unlink(2, 1);
    const Host::Reply r = host.next();
    EXPECT_EQ(r.command, kRetUnlink);
    EXPECT_EQ(r.seqnum, 2u);
    EXPECT_EQ(r.status, -ECONNRESET);
    EXPECT_FALSE(device.complete_in(kBulkEp, std::vector<std::uint8_t>(16)));  // nothing left to answer
}

TEST(UsbipLink, UnlinkingACompletedTransferAnswersZero) {
    Host host;
    UsbipDevice device(no_control, host.device_end());
    submit_and_complete(host, device, 1);
    host.unlink(2, 1);
    const Host::Reply r = host.next();
    EXPECT_EQ(r.command, kRetUnlink);
    EXPECT_EQ(r.seqnum, 2u);
    EXPECT_EQ(r.status, 0);
}

// vhci may send a transfer's unlink before the transfer itself (both queued
// between two passes of its sender). The transfer must then be cancelled,
// never completed: vhci gives it back on the RET_UNLINK, and a RET_SUBMIT
// after that finds nothing there and drops the device.
TEST(UsbipLink, AnUnlinkThatOvertakesItsTransferCancelsItWhenItArrives) {
    Host host;
    UsbipDevice device(no_control, host.device_end());
    submit_and_complete(host, device, 1);
    host.unlink(3, 2);     // transfer 2's unlink, first
    host.submit_in(2, 8);  // then transfer 2
    host.submit_in(4, 8);  // and a later one, which is served as usual
    const Host::Reply cancelled = host.next();
    EXPECT_EQ(cancelled.command, kRetUnlink);
    EXPECT_EQ(cancelled.seqnum, 3u);
    EXPECT_EQ(cancelled.status, -ECONNRESET);
    ASSERT_TRUE(device.next_in(kBulkEp, 5.0));
    ASSERT_TRUE(device.complete_in(kBulkEp, std::vector<std::uint8_t>(8, 7)));
    const Host::Reply next = host.next();
    EXPECT_EQ(next.command, kRetSubmit);
    EXPECT_EQ(next.seqnum, 4u) << "transfer 2 was answered after its cancellation";
    EXPECT_FALSE(device.next_in(kBulkEp, 0.05));
}

// A link plugged into a port vhci has just let go of may be sent the old
// device's cancellations: transfers this link never had. Held for a submit
// that never comes, they would keep usbcore waiting for ever (the device never
// re-enumerates). Before any submit, an unlink is answered at once; once
// submits flow, one is answered as soon as a later-numbered submit shows its
// transfer will not come (vhci sends a port's submits in order).
TEST(UsbipLink, UnlinksOfTransfersThatCannotComeAreAnsweredAtOnce) {
    Host host;
    UsbipDevice device(no_control, host.device_end());
    host.unlink(1001, 900);  // before any submit on this link
    const Host::Reply first = host.next();
    EXPECT_EQ(first.command, kRetUnlink);
    EXPECT_EQ(first.seqnum, 1001u);
    EXPECT_EQ(first.status, -ECONNRESET);
    host.submit_in(900, 8);  // should it come after all, it is not answered
    submit_and_complete(host, device, 1002);
    host.unlink(1004, 1003);  // held: 1003 may still come ...
    host.submit_in(1005, 8);  // ... until a later one does
    const Host::Reply passed = host.next();
    EXPECT_EQ(passed.command, kRetUnlink);
    EXPECT_EQ(passed.seqnum, 1004u);
    EXPECT_EQ(passed.status, -ECONNRESET);
    ASSERT_TRUE(device.next_in(kBulkEp, 5.0));
    ASSERT_TRUE(device.complete_in(kBulkEp, std::vector<std::uint8_t>(8)));
    const Host::Reply served = host.next();
    EXPECT_EQ(served.command, kRetSubmit);
    EXPECT_EQ(served.seqnum, 1005u);
}

}  // namespace
}  // namespace vkfuse::test

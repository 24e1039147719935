// vkfuse-digit-emulator: an emulated DIGIT that the kernel's own uvcvideo
// driver talks to, for hardware-in-the-loop tests (tests/hil). Plugged into
// the kernel's virtual USB host controller (vhci_hcd, USB/IP's) it is a USB
// device with the DIGIT's identity and modes (uvc_descriptors.hpp,
// uvc_camera.hpp, usbip_device.hpp), and it streams frames of the simulated
// DIGIT lit as the zoom control last said (renderer.hpp). Needs root (vhci's
// attach file) and the vhci_hcd module.
//
//   vkfuse-digit-emulator --serial D20001 [--firmware 0200] [--latency-ms 25]
//       [--corrupt-mjpeg-every N] [--object coin] [--prerender 15,0,0+0,15,0]
//       [--vhci /sys/devices/platform/vhci_hcd.0]
//
// Prints "digit-emulator: ready <serial> <host /dev/videoN>" once the host has
// its capture node. Signals: SIGUSR1 unplugs (the link closes: the host sees
// the device go), SIGUSR2 plugs it back, SIGHUP stops or resumes the stream
// (a silent camera), SIGTERM / SIGINT unplug and exit. Several emulators may
// run at once, each on a port of its own.
// VKFUSE_EMULATOR_TRACE=1 prints every control request the host makes.
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "uvc_camera.hpp"
#include "renderer.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/digit.hpp"

namespace vkfuse::emulator {
namespace {

struct Options {
    CameraSpec camera;
    RendererOptions render;
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc) throw Error(ErrorKind::InvalidArgument, a + ": needs a value");
        const std::string v = argv[++i];
        if (a == "--serial") o.camera.serial = v;
        else if (a == "--firmware") o.camera.bcd_device = std::uint16_t(std::stoul(v, nullptr, 16));
        else if (a == "--vhci") o.camera.vhci = v;
        else if (a == "--latency-ms") o.render.led_latency_s = std::stod(v) / 1000.0;
        else if (a == "--corrupt-mjpeg-every") o.render.corrupt_mjpeg_every = std::stoi(v);
        else if (a == "--object") o.render.object = v;
        else if (a == "--prerender") o.render.prerender = parse_sequence(v);
        else throw Error(ErrorKind::InvalidArgument, a + ": unknown option");
    }
    o.render.serial = o.camera.serial;
    return o;
}

// The host's capture node for our serial, once uvcvideo has made it.
std::string host_node(const std::string& serial, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < end) {
        for (const DigitDevice& d : find_digits())
            if (d.serial == serial && !d.video_nodes.empty()) return d.video_nodes.front();
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    throw Error(ErrorKind::Device, serial + ": the host made no capture node within " +
                                       std::to_string(int(timeout_s)) + " s");
}

int run(Options o) {
    sigset_t signals;
    sigemptyset(&signals);
    for (int s : {SIGTERM, SIGINT, SIGUSR1, SIGUSR2, SIGHUP}) sigaddset(&signals, s);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before any thread starts: all inherit it
    const int sfd = ::signalfd(-1, &signals, SFD_CLOEXEC);

    char bcd[8];
    std::snprintf(bcd, sizeof bcd, "%04x", o.camera.bcd_device);
    const DigitFirmware fw = DigitFirmware::from_bcd(bcd).value_or(DigitFirmware{2, 0});
    o.camera.zoom = fw.per_led_levels() ? ZoomRange{0, 0x0fff, 1, 0x0fff} : ZoomRange{0, 255, 1, 255};

    // Unplugging closes the device's link; plugging it back attaches a new
    // one, as a cable would. The renderer reaches the
    // camera of the moment through `plugged`.
    std::mutex mutex;
    std::shared_ptr<UvcCamera> plugged;
    const auto current = [&] {
        std::lock_guard lock(mutex);
        return plugged;
    };
    std::unique_ptr<Renderer> renderer;
    const auto plug = [&] {
        auto camera = std::make_shared<UvcCamera>(o.camera, [&](std::uint16_t v) {
            if (renderer)
                renderer->set_illumination(digit_led_setting(v, fw, {o.camera.zoom.minimum, o.camera.zoom.maximum}));
        });
        std::lock_guard lock(mutex);
        plugged = std::move(camera);
    };
    const auto unplug = [&] {
        std::shared_ptr<UvcCamera> gone;
        {
            std::lock_guard lock(mutex);
            gone.swap(plugged);
        }
        if (gone) gone->unplug();
    };
    renderer = std::make_unique<Renderer>(
        o.render,
        [&]() -> std::optional<Committed> {
            const auto camera = current();
            return camera ? camera->streaming() : std::nullopt;
        },
        [&](const Committed& c, std::size_t size, const FrameBytes& frame) {
            const auto camera = current();
            return camera && camera->send_frame(c, size, frame);
        });
    plug();

    const auto ready = [&] {
        std::printf("digit-emulator: ready %s %s\n", o.camera.serial.c_str(), host_node(o.camera.serial, 60).c_str());
        std::fflush(stdout);
    };
    ready();
    for (;;) {
        signalfd_siginfo si{};
        if (::read(sfd, &si, sizeof si) != sizeof si) continue;
        if (si.ssi_signo == SIGUSR1) {
            unplug();
            std::printf("digit-emulator: unplugged %s\n", o.camera.serial.c_str());
            std::fflush(stdout);
        } else if (si.ssi_signo == SIGUSR2) {
            plug();
            ready();
        } else if (si.ssi_signo == SIGHUP) {
            renderer->pause(!renderer->paused());
        } else {
            break;
        }
    }
    unplug();
    renderer.reset();
    return 0;
}

}  // namespace
}  // namespace vkfuse::emulator

int main(int argc, char** argv) {
    try {
        return vkfuse::emulator::run(vkfuse::emulator::parse(argc, argv));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "digit-emulator: %s\n", e.what());
        return 1;
    }
}

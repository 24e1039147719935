// uvc_camera.hpp - an emulated DIGIT as a USB device: it answers the host's
// control requests (descriptors, configuration, UVC stream negotiation, the
// zoom control that carries the LED value) and streams frames as UVC
// payloads over its bulk endpoint, one payload per frame, each cut into the
// host's bulk transfers as they come.
//
//   host uvcvideo --control--> vhci_hcd --> UsbipDevice --> UvcCamera::control (answers)
//   Renderer --send_frame--> header + rows, as exposed --> UsbipDevice::complete_in --> uvcvideo
//
// A bulk streaming endpoint is what uvcvideo supports on any UVC camera; the
// emulator needs no isochronous timing, and the host's transfer sizes pace it.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "usbip_device.hpp"
#include "uvc_descriptors.hpp"

namespace vkfuse::emulator {

struct ZoomRange {
    std::uint16_t minimum = 0, maximum = 0x0fff, step = 1, default_value = 0x0fff;
};

struct CameraSpec {
    std::string serial = "D20001";
    std::uint16_t bcd_device = 0x0200;
    std::string vhci = "/sys/devices/platform/vhci_hcd.0";  // the virtual host controller's sysfs directory
    ZoomRange zoom;
};

// Gives the frame's first `bytes` bytes (composing what is not yet there,
// waiting for those rows to be exposed); returns the frame's start.
using FrameBytes = std::function<const std::uint8_t*(std::size_t bytes)>;

class UvcCamera {
public:
    // Plugs the camera into the virtual host controller; the host enumerates
    // it at once. on_zoom runs with each value the host sets.
    UvcCamera(const CameraSpec& spec, std::function<void(std::uint16_t)> on_zoom);

    // The mode the host committed to, while it streams.
    std::optional<Committed> streaming() const;
    // Streams one frame of `frame_size` bytes as one UVC payload, taking its
    // bytes from `frame` as each of the host's transfers asks for more. False
    // when the host stopped streaming `c` or the camera is unplugged.
    bool send_frame(const Committed& c, std::size_t frame_size, const FrameBytes& frame);
    // Pulls the cable (the host sees the device go), while others may still
    // hold the object.
    void unplug();

private:
    ControlReply control(const SetupPacket& s, std::span<const std::uint8_t> out);
    ControlReply standard_request(const SetupPacket& s);
    ControlReply streaming_request(const SetupPacket& s, std::span<const std::uint8_t> out);
    ControlReply zoom_request(const SetupPacket& s, std::span<const std::uint8_t> out);
    Committed clamp(std::span<const std::uint8_t> probe) const;
    // Whether the host still streams the mode c committed (streams_locked:
    // with mutex_ held).
    bool still_streaming(const Committed& c) const;
    bool streams_locked(const Committed& c) const;

    CameraSpec spec_;
    std::function<void(std::uint16_t)> on_zoom_;
    std::vector<StreamMode> modes_ = digit_stream_modes();

    mutable std::mutex mutex_;  // the state below: control requests set it, send_frame reads it
    std::uint16_t zoom_value_;
    Committed probe_, commit_;
    bool streaming_ = false;
    std::uint8_t fid_ = 0;

    std::unique_ptr<UsbipDevice> device_;  // last: it serves control() until destroyed
};

}  // namespace vkfuse::emulator

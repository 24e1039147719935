// gadgetfs_camera.hpp - an emulated DIGIT on a USB device controller through
// GadgetFS: the user-space program is the device. It hands the kernel its
// descriptors, answers the host's control requests on endpoint 0 (strings,
// configuration, UVC stream negotiation, the zoom control that carries the
// LED value) and writes each frame to its bulk endpoint as one UVC payload.
//
//   host uvcvideo --SETUP--> dummy_hcd/dummy_udc --> gadgetfs ep0 --> GadgetfsCamera (answers)
//   renderer --submit(frame)--> header + frame --> gadgetfs ep1in-bulk --> host URBs --> uvcvideo
//
// The kernel's own UVC gadget function streams only over isochronous
// endpoints, which neither dummy_hcd nor USB/IP's virtual UDC carries; a bulk
// streaming endpoint, which uvcvideo supports as any UVC camera's, does.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "uvc_descriptors.hpp"

struct usb_ctrlrequest;
struct usb_gadgetfs_event;

namespace vkfuse::emulator {

struct ZoomRange {
    std::uint16_t minimum = 0, maximum = 0x0fff, step = 1, default_value = 0x0fff;
};

struct CameraSpec {
    std::string serial = "D20001";
    std::uint16_t bcd_device = 0x0200;
    std::string gadgetfs = "/dev/gadget";  // where gadgetfs is mounted
    std::string udc = "dummy_udc";         // the ep0 file's name there
    ZoomRange zoom;
};

class GadgetfsCamera {
public:
    // Registers the device and answers endpoint 0 on a thread of its own from
    // then on: GadgetFS hands control requests to user space only while a
    // read of ep0 is pending, and the host enumerates as soon as the
    // descriptors are in. on_zoom runs on that thread with each value the host sets.
    GadgetfsCamera(const CameraSpec& spec, std::function<void(std::uint16_t)> on_zoom);
    ~GadgetfsCamera();
    GadgetfsCamera(const GadgetfsCamera&) = delete;
    GadgetfsCamera& operator=(const GadgetfsCamera&) = delete;

    // The mode the host committed to, while it streams.
    std::optional<Committed> streaming() const;
    // Writes one frame as a UVC payload (blocks until the host has read it);
    // false when the host is not streaming `c` any more or the write failed.
    bool submit(const Committed& c, std::span<const std::uint8_t> frame);
    bool configured() const;
    // Unregisters the device now (the host sees it go; a frame write in
    // flight fails), while others may still hold the object.
    void unplug();

private:
    void serve();
    void handle(const ::usb_gadgetfs_event* events, std::size_t n);
    void on_setup(const ::usb_ctrlrequest& req);
    void on_class_request(const ::usb_ctrlrequest& req);
    void answer(std::span<const std::uint8_t> data, std::uint16_t length);
    void ack();
    void stall(bool in);
    void configure(bool on);
    void stop_stream();
    std::vector<std::uint8_t> streaming_control(const Committed& c) const;
    Committed clamp(std::span<const std::uint8_t> probe) const;

    CameraSpec spec_;
    std::function<void(std::uint16_t)> on_zoom_;
    std::vector<StreamMode> modes_ = digit_stream_modes();
    int ep0_ = -1;
    bool high_speed_ = true;
    std::uint16_t zoom_value_;
    Committed probe_, commit_;

    mutable std::mutex mutex_;  // the stream state below, shared with the renderer's submit()
    std::condition_variable idle_;
    int ep_in_ = -1;
    bool writing_ = false;
    bool streaming_ = false;
    std::uint8_t fid_ = 0;

    std::mutex unplug_mutex_;
    std::atomic<bool> stop_{false};
    std::thread ep0_thread_;
};

}  // namespace vkfuse::emulator

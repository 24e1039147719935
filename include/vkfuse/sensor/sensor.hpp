// vkfuse/sensor/sensor.hpp - what a vision-based tactile sensor offers vkfuse: a
// real DIGIT over V4L2/libusb, the simulated DIGIT, or a recorded dataset.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vkfuse/core/image.hpp"
#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse {

struct SensorInfo {
    std::string model;    // "DIGIT", "DIGIT (simulated)", "dataset"
    std::string serial;   // unique per sensor; errors are reported with it
    int width = 0;
    int height = 0;
    double fps = 0;
    LedLayout leds;
};

// One captured frame: 8-bit RGB, HWC.
struct Frame {
    std::uint64_t index = 0;       // frame counter of this sensor, from 0
    double timestamp = 0;          // start of exposure of the first row, seconds (sensor clock)
    int height = 0;
    int width = 0;
    std::vector<std::uint8_t> pixels;  // height * width * 3
    // The setting that lit the whole frame, when the sensor knows it (a real
    // DIGIT does not; a dataset replays what was recorded).
    std::optional<Illumination> illumination;
    // A replayed frame: the rig cycle it was fused in when recorded (a Rig
    // then places it in that very cycle); -1 for a live frame.
    std::int64_t recorded_cycle = -1;
    // A frame another host's rig took: which rig (a number all its sensors'
    // frames share; 0 for none) and the cycle it took it in. A Rig keeps the
    // sensors of one origin in step: a sensor whose next frames are for a
    // later cycle than another's (its cycle was lost on the way) sits the
    // earlier cycle out rather than be fused beside it, and the others do not
    // fall a cycle behind for good.
    std::uint64_t origin = 0;
    std::uint64_t origin_cycle = 0;

    FrameView view() const { return {pixels.data(), height, width, 3, PixelType::U8}; }
};

// A sensor is used by one thread at a time. Errors throw vkfuse::Error naming the serial.
class Sensor {
public:
    virtual ~Sensor() = default;
    virtual SensorInfo info() const = 0;
    // Requests a new LED setting now; it takes effect after the sensor's own
    // latency (frames grabbed meanwhile may be lit by the old one or a mix).
    virtual void set_illumination(const Illumination& setting) = 0;
    // The next frame, waiting for it on the sensor's clock.
    virtual Frame grab() = 0;
};

}  // namespace vkfuse

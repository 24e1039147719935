// vkfuse/sim_digit.hpp - a physically plausible simulated DIGIT: gel, three
// rim LEDs, objects pressed into the gel, camera noise, LED switching latency
// and a rolling shutter. Deterministic for a seed and a virtual clock.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vkfuse/clock.hpp"
#include "vkfuse/sensor.hpp"

namespace vkfuse {

struct SimDigitOptions {
    std::uint64_t seed = 1;
    bool vga = false;               // false: QVGA 320x240 at 60 fps; true: VGA 640x480 at 30 fps
    std::string object = "coin";    // one of SimDigit::objects()
    double press_depth_mm = 1.0;    // how far the object is pressed into the gel
    double x = 0.5, y = 0.5;        // contact centre, fraction of width / height
    double led_latency_s = 1.5 / 60.0;  // a new setting takes effect this long after it is requested
    std::string serial = "SIM-0001";
    std::shared_ptr<Clock> clock;   // null: a virtual clock of its own
};

// What really lit one frame (the simulator knows; a real sensor does not).
struct SimFrameTruth {
    std::uint64_t index = 0;
    bool mixed = false;             // some rows saw the old setting, some the new
    Illumination lit_by;            // the setting of the whole frame when !mixed
};

class SimDigit : public Sensor {
public:
    explicit SimDigit(const SimDigitOptions& options = {});
    ~SimDigit() override;

    SensorInfo info() const override;
    void set_illumination(const Illumination& setting) override;
    Frame grab() override;

    // Ground truth of a frame this sensor produced (the most recent frames are kept).
    SimFrameTruth truth(std::uint64_t frame_index) const;
    // Change what is pressed into the gel ("nothing" for the background).
    void set_object(const std::string& object, double press_depth_mm = 1.0);

    // Built-in objects: "nothing", "coin-heads", "coin-tails", "lego", "ball",
    // "screw", "nut", "velcro", "file", "text" (and "coin" = "coin-heads").
    static std::vector<std::string> objects();

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse

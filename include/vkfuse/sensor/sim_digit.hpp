// vkfuse/sensor/sim_digit.hpp - a physically plausible simulated DIGIT: gel, three
// rim LEDs, objects pressed into the gel, camera noise, LED switching latency
// and a rolling shutter. Deterministic for a seed and a virtual clock.
//
// Frames are landscape, as the DIGIT's image sensor streams them: QVGA is 320
// wide x 240 high. digit_interface's Digit.get_frame() (and so TACTO's
// background bg_digit_240_320.jpg) turns them portrait by transposing and
// flipping vertically: portrait(i, j) = landscape(j, 319 - i).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse {

// How the pressed object moves, timed from the moment it was pressed (the
// sensor's construction, or set_object / move_object). A frame shows the
// contact of its timestamp, the start of its row 0: the rows of one frame
// never see two contacts.
enum class SimMotion {
    Still,  // stays as pressed
    Tap,    // pressed for the first half of every period, lifted clear of the gel for the second
    // Slides across the middle of the gel at its press depth and y: the centre
    // goes from x = 0.25 to 0.75 of the width and back once per period, in
    // steps of 1/16 of the width. The 9 positions are rendered when the object
    // is pressed (a few seconds), so the sensor keeps its frame rate after.
    Slide,
};
std::string_view to_string(SimMotion motion);  // "still", "tap", "slide"
// Throws Error(InvalidArgument) "<what>: unknown motion ..." naming the choices.
SimMotion parse_sim_motion(std::string_view name, std::string_view what = "--motion");

struct SimDigitOptions {
    std::uint64_t seed = 1;         // camera noise; everything else is deterministic physics
    bool vga = false;               // false: QVGA 320x240 at 60 fps; true: VGA 640x480 at 30 fps
    std::string object = "coin";    // one of SimDigit::objects() (or "coin" = "coin-heads")
    double press_depth_mm = 1.0;    // how far the object is pressed into the gel, 0..2.5
    double x = 0.5, y = 0.5;        // contact centre, fraction of width / height, 0..1
    SimMotion motion = SimMotion::Still;
    double motion_period_s = 2.0;   // one tap, or one slide there and back; >= kMinMotionPeriodS
    // Three frames at 60 fps: anything faster shows no motion, only aliasing.
    static constexpr double kMinMotionPeriodS = 0.05;
    // A new setting takes effect this long after it is requested (USB request,
    // firmware, LED driver). Frames exposed across that moment are mixed.
    double led_latency_s = 1.5 / 60.0;
    // The camera's auto exposure and auto white balance, on as the DIGIT
    // streams: after a switch they need a few frames to settle, so together
    // with the latency a frame is right about 0.1 s after the request, as the
    // paper found. false: fixed nominal exposure and unity gains.
    bool camera_auto = true;
    std::string serial = "SIM-0001";
    std::shared_ptr<Clock> clock;   // null: a virtual clock of its own
};

// The rolling shutter: row r of frame n is exposed during
// [t_n + r * row_time_s, t_n + r * row_time_s + exposure], t_n = t_0 + n * frame_period_s
// (t_0: the clock's time when the sensor was made). The exposure is the
// frame's own (SimFrameTruth::exposure_s, set by auto exposure between
// min_exposure_s and max_exposure_s; nominal_exposure_s without it).
struct SimTiming {
    double frame_period_s = 0;
    double row_time_s = 0;
    double nominal_exposure_s = 0;
    double min_exposure_s = 0;
    double max_exposure_s = 0;
    int rows = 0;
    // From the start of row 0 to the end of the last row for a given exposure:
    // a frame is complete (grab() returns it) this long after its timestamp.
    double frame_span_s(double exposure_s) const { return (rows - 1) * row_time_s + exposure_s; }
};

// What really lit one frame (the simulator knows; a real sensor does not).
struct SimFrameTruth {
    std::uint64_t index = 0;
    double timestamp = 0;           // the frame's timestamp (start of row 0)
    bool mixed = false;             // some rows saw one setting, some another
    Illumination lit_by;            // the setting of the whole frame when !mixed; empty when mixed
    std::vector<Illumination> settings;  // every setting that lit some row, in time order
    // How the camera read it out: exposure time, analog gain and the white
    // balance gains (r, g, b). They settle over a few frames after the light
    // changes; a frame whose values equal its predecessor's is settled.
    double exposure_s = 0;
    double analog_gain = 1;
    std::array<double, 3> white_balance{1, 1, 1};
    // What touched the gel: the object ("nothing" when lifted or never
    // pressed) and its centre (fractions of width and height).
    std::string object;
    double contact_x = 0, contact_y = 0;
};

class SimDigit : public Sensor {
public:
    // Throws Error(InvalidArgument) naming the serial for an unknown object or
    // an out-of-range depth, position or latency.
    explicit SimDigit(const SimDigitOptions& options = {});
    ~SimDigit() override;

    SensorInfo info() const override;
    // Starts at (15,15,15), like a DIGIT after power-up. The new setting takes
    // effect at clock->now() + led_latency_s; with the sensor's own virtual
    // clock, now() is the end of the last grabbed frame. Throws
    // Error(InvalidArgument) "<serial>: illumination 16,0,0: ..." when the
    // setting does not fit LedLayout::digit().
    void set_illumination(const Illumination& setting) override;
    // The next frame (illumination = nullopt: the rig infers it from time).
    // Waits on the clock until the frame's last row is exposed. If the clock
    // has run past later frames meanwhile (a shared clock advanced by someone
    // else, a slow caller on a real clock), the sensor has streamed on: it
    // returns the newest complete frame and the skipped indices never appear.
    Frame grab() override;

    // Frame frame_index as the camera would read it out lit by setting alone
    // and showing the contact of time contact_time (the sensor's clock, as
    // frame timestamps) instead of its own: the same camera
    // noise and the ISP's present readout. A grabbed frame that setting lit
    // alone and that saw that contact comes out byte for byte. Rendering each
    // slot of a window at one instant gives the frames a sliding window (or a
    // cycle) stands in for: every setting at the same moment. Throws
    // Error(InvalidArgument) naming the serial for a setting that does not fit.
    Frame render(std::uint64_t frame_index, const Illumination& setting, double contact_time) const;

    // Ground truth of a frame this sensor produced; the last 4096 are kept.
    // Throws Error(InvalidArgument) for any other index.
    SimFrameTruth truth(std::uint64_t frame_index) const;
    SimTiming timing() const;
    // Change what is pressed into the gel ("nothing" for the background), at
    // the current position. Takes effect from the next grabbed frame; the
    // motion (SimDigitOptions::motion) starts over from the clock's now().
    void set_object(const std::string& object, double press_depth_mm = 1.0);
    // Move the contact centre (fractions of width / height, 0..1); the motion
    // starts over from there.
    void move_object(double x, double y);

    // Built-in objects: "nothing", "coin-heads", "coin-tails", "lego", "ball",
    // "screw", "nut", "velcro", "file", "text" (and "coin" = "coin-heads").
    static std::vector<std::string> objects();

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse

// The simulated DIGIT as a Sensor (include/vkfuse/sensor/sim_digit.hpp): time,
// LED requests, press motion and frame bookkeeping; the physics lives in the
// rest of src/sim/.
#include "vkfuse/sensor/sim_digit.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "sim/camera.hpp"
#include "sim/isp.hpp"
#include "sim/lighting.hpp"
#include "sim/motion.hpp"
#include "sim/relief.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

constexpr double kMaxDepthMm = 2.5;        // about the DIGIT gel's thickness
constexpr std::size_t kTruthsKept = 4096;
// A late caller gets the newest frame; the ISP still saw the frames it
// skipped, but after this many it has settled whatever came before.
constexpr std::uint64_t kSkippedFramesMetered = 16;

Illumination power_on() { return Illumination({15, 15, 15}); }

[[noreturn]] void fail(const std::string& serial, const std::string& problem) {
    throw Error(ErrorKind::InvalidArgument, serial + ": " + problem);
}

void check_object(const std::string& serial, const std::string& object, double depth_mm) {
    if (!sim::make_relief(object)) {
        std::string known;
        for (const std::string& name : sim::relief_names()) known += (known.empty() ? "" : ", ") + name;
        fail(serial, "unknown object \"" + object + "\" (expected " + known + ")");
    }
    if (!(depth_mm >= 0 && depth_mm <= kMaxDepthMm))
        fail(serial, "press depth " + std::to_string(depth_mm) + " mm is outside 0.." + std::to_string(kMaxDepthMm));
}

void check_position(const std::string& serial, double x, double y) {
    if (!(x >= 0 && x <= 1 && y >= 0 && y <= 1))
        fail(serial, "object position (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside 0..1");
}

const SimDigitOptions& checked(const SimDigitOptions& o) {
    check_object(o.serial, o.object, o.press_depth_mm);
    check_position(o.serial, o.x, o.y);
    if (!(o.led_latency_s >= 0 && std::isfinite(o.led_latency_s)))
        fail(o.serial, "LED latency " + std::to_string(o.led_latency_s) + " s is not a time >= 0");
    if (!(o.motion_period_s >= SimDigitOptions::kMinMotionPeriodS && std::isfinite(o.motion_period_s)))
        fail(o.serial, "motion period " + std::to_string(o.motion_period_s) + " s is not a time >= " +
                           std::to_string(SimDigitOptions::kMinMotionPeriodS) + " s");
    return o;
}

// What the ISP steers to: the untouched gel at the power-on setting with the
// nominal readout - the state the real DIGIT frame we calibrate against was
// taken in (its brightness and its white point).
sim::IspTarget isp_target(const sim::Grid& grid, const sim::LedRig& rig) {
    const sim::LedImages flat = sim::render_scene({}, grid, rig);
    double mean[3] = {0, 0, 0};
    for (const std::vector<float>& led : flat)
        for (std::size_t i = 0; i < led.size(); ++i) mean[i % 3] += led[i] / double(grid.size());
    return {0.299 * mean[0] + 0.587 * mean[1] + 0.114 * mean[2], mean[0] / mean[1], mean[2] / mean[1]};
}

}  // namespace

struct SimDigit::Impl {
    SimDigitOptions options;
    sim::Grid grid;
    sim::ShutterTiming shutter;
    sim::LedRig rig = sim::digit_led_rig();
    sim::CameraNoise noise = sim::CameraNoise::digit();
    sim::IspLimits limits;
    sim::Isp isp;
    LedLayout layout = LedLayout::digit();
    std::shared_ptr<Clock> clock;
    double start = 0;  // t_0
    sim::LedTimeline timeline{power_on()};
    sim::Contact pressed;       // as set; the motion moves it from there
    double pressed_since = 0;   // when it was set: the motion's time 0
    sim::MotionScenes scenes;   // every contact the motion visits, rendered
    std::uint64_t next = 0;
    std::deque<SimFrameTruth> truths;

    explicit Impl(const SimDigitOptions& o)
        : options(checked(o)),
          grid(o.vga ? sim::Grid::vga() : sim::Grid::qvga()),
          shutter(sim::ShutterTiming::for_stream(o.vga ? 30.0 : 60.0, grid.height)),
          isp(isp_target(grid, rig), o.camera_auto, limits),
          clock(o.clock ? o.clock : make_virtual_clock()),
          start(clock->now()),
          pressed{o.object == "coin" ? "coin-heads" : o.object, o.press_depth_mm, o.x, o.y},
          pressed_since(start),
          scenes(pressed, o.motion, grid, rig) {}

    // Presses `contact` now: the motion starts over from it.
    void press(const sim::Contact& contact) {
        scenes = sim::MotionScenes(contact, options.motion, grid, rig);
        pressed = contact;
        pressed_since = clock->now();
    }

    sim::Contact contact_of(std::uint64_t n) const {
        return sim::contact_at(pressed, options.motion, options.motion_period_s, frame_start(n) - pressed_since);
    }

    double frame_start(std::uint64_t n) const { return start + double(n) * shutter.frame_period; }
    double exposure() const { return shutter.nominal_exposure * isp.readout().exposure_scale; }
    double frame_end(std::uint64_t n) const { return frame_start(n) + shutter.span(exposure()); }

    // The frame to deliver now: the next in sequence unless the clock has
    // already passed the end of later ones (the sensor streamed on).
    std::uint64_t pick_index() const {
        const double done = (clock->now() - start - shutter.span(exposure())) / shutter.frame_period;
        if (done < 0) return next;
        return std::max(next, std::uint64_t(std::floor(done + 1e-9)));
    }

    std::vector<std::array<double, 3>> row_drives(double t) const { return row_drives(t, timeline); }
    std::vector<std::array<double, 3>> row_drives(double t, const sim::LedTimeline& lit) const {
        std::vector<std::array<double, 3>> drives(std::size_t(grid.height));
        for (int r = 0; r < grid.height; ++r) {
            const double begin = t + r * shutter.row_time;
            drives[std::size_t(r)] = lit.mean_drive(begin, begin + exposure(), layout.max_level);
        }
        return drives;
    }

    void record(std::uint64_t n, const sim::Contact& contact) {
        const double t = frame_start(n);
        const sim::Readout& r = isp.readout();
        SimFrameTruth truth{n, t, false, {}, timeline.settings_during(t, frame_end(n)), exposure(), r.analog_gain,
                            r.white_balance, contact.object, contact.x, contact.y};
        truth.mixed = truth.settings.size() > 1;
        if (!truth.mixed) truth.lit_by = truth.settings.front();
        truths.push_back(std::move(truth));
        if (truths.size() > kTruthsKept) truths.pop_front();
    }

    // Reads frame n out with the ISP's current settings, then lets the ISP meter it.
    Frame read_out(std::uint64_t n, bool deliver) {
        Frame frame{n, frame_start(n), grid.height, grid.width, std::vector<std::uint8_t>(grid.size() * 3), std::nullopt};
        sim::NoiseStream rng(options.seed, n);
        const sim::Contact contact = contact_of(n);
        sim::expose(scenes.images(contact), row_drives(frame.timestamp), grid.width, isp.readout(), noise, rng,
                    frame.pixels.data());
        if (deliver) record(n, contact);
        isp.meter(frame.pixels.data(), grid.size());
        return frame;
    }
};

SimDigit::SimDigit(const SimDigitOptions& options) : impl_(std::make_unique<Impl>(options)) {}
SimDigit::~SimDigit() = default;

SensorInfo SimDigit::info() const {
    const Impl& s = *impl_;
    return {"DIGIT (simulated)", s.options.serial, s.grid.width, s.grid.height, 1.0 / s.shutter.frame_period, s.layout};
}

void SimDigit::set_illumination(const Illumination& setting) {
    try {
        setting.check(impl_->layout);
    } catch (const Error& e) {
        fail(impl_->options.serial, e.what());
    }
    impl_->timeline.change(impl_->clock->now() + impl_->options.led_latency_s, setting);
}

Frame SimDigit::grab() {
    Impl& s = *impl_;
    const std::uint64_t n = s.pick_index();
    // Frames streamed while nobody asked were still metered by the ISP.
    for (std::uint64_t k = std::max(s.next, n > kSkippedFramesMetered ? n - kSkippedFramesMetered : 0); k < n; ++k)
        s.read_out(k, false);
    s.clock->wait_until(s.frame_end(n));
    Frame frame = s.read_out(n, true);
    s.next = n + 1;
    // What lit frames before n + 1 can no longer matter.
    s.timeline.forget_before(s.frame_start(s.next));
    return frame;
}

Frame SimDigit::render(std::uint64_t frame_index, const Illumination& setting, double contact_time) const {
    const Impl& s = *impl_;
    try {
        setting.check(s.layout);
    } catch (const Error& e) {
        fail(s.options.serial, e.what());
    }
    Frame frame{frame_index, s.frame_start(frame_index), s.grid.height, s.grid.width,
                std::vector<std::uint8_t>(s.grid.size() * 3), setting};
    sim::NoiseStream rng(s.options.seed, frame_index);
    const sim::Contact contact =
        sim::contact_at(s.pressed, s.options.motion, s.options.motion_period_s, contact_time - s.pressed_since);
    sim::expose(s.scenes.images(contact), s.row_drives(frame.timestamp, sim::LedTimeline(setting)), s.grid.width,
                s.isp.readout(), s.noise, rng, frame.pixels.data());
    return frame;
}

SimFrameTruth SimDigit::truth(std::uint64_t frame_index) const {
    for (const SimFrameTruth& t : impl_->truths)
        if (t.index == frame_index) return t;
    fail(impl_->options.serial, "no ground truth kept for frame " + std::to_string(frame_index));
}

SimTiming SimDigit::timing() const {
    const Impl& s = *impl_;
    const double nominal = s.shutter.nominal_exposure;
    return {s.shutter.frame_period, s.shutter.row_time, nominal, nominal * s.limits.min_exposure_scale,
            nominal * s.limits.max_exposure_scale, s.shutter.rows};
}

void SimDigit::set_object(const std::string& object, double press_depth_mm) {
    check_object(impl_->options.serial, object, press_depth_mm);
    sim::Contact contact = impl_->pressed;
    contact.object = object == "coin" ? "coin-heads" : object;
    contact.depth_mm = press_depth_mm;
    impl_->press(contact);
}

void SimDigit::move_object(double x, double y) {
    check_position(impl_->options.serial, x, y);
    sim::Contact contact = impl_->pressed;
    contact.x = x;
    contact.y = y;
    impl_->press(contact);
}

std::vector<std::string> SimDigit::objects() { return sim::relief_names(); }

}  // namespace vkfuse

// Press motion: still, tap and slide (sim/motion.hpp).
#include "sim/motion.hpp"

#include <cmath>
#include <stdexcept>

#include "vkfuse/core/error.hpp"

namespace vkfuse {

std::string_view to_string(SimMotion motion) {
    switch (motion) {
        case SimMotion::Still: return "still";
        case SimMotion::Tap: return "tap";
        case SimMotion::Slide: return "slide";
    }
    return "?";
}

SimMotion parse_sim_motion(std::string_view name, std::string_view what) {
    for (SimMotion m : {SimMotion::Still, SimMotion::Tap, SimMotion::Slide})
        if (to_string(m) == name) return m;
    throw Error(ErrorKind::InvalidArgument,
                std::string(what) + ": unknown motion \"" + std::string(name) + "\" (expected still, tap or slide)");
}

namespace sim {
namespace {

// A slide's centre: 0.25 .. 0.75 of the width in steps of 1/16, out and back.
constexpr int kSlideSteps = 8;
constexpr double kSlideFrom = 0.25, kSlideStep = 1.0 / 16;

Contact lifted(const Contact& pressed) {
    Contact c;  // "nothing" at depth 0: the untouched gel
    c.x = pressed.x;
    c.y = pressed.y;
    return c;
}

Contact slid(const Contact& pressed, int step) {
    Contact c = pressed;
    c.x = kSlideFrom + step * kSlideStep;
    return c;
}

bool touches(const Contact& c) { return c.object != "nothing"; }

}  // namespace

std::vector<Contact> motion_contacts(const Contact& pressed, SimMotion motion) {
    if (!touches(pressed)) return {pressed};
    switch (motion) {
        case SimMotion::Still: return {pressed};
        case SimMotion::Tap: return {pressed, lifted(pressed)};
        case SimMotion::Slide: {
            std::vector<Contact> out;
            for (int step = 0; step <= kSlideSteps; ++step) out.push_back(slid(pressed, step));
            return out;
        }
    }
    return {pressed};
}

Contact contact_at(const Contact& pressed, SimMotion motion, double period_s, double since) {
    if (!touches(pressed) || motion == SimMotion::Still) return pressed;
    const double cycles = std::max(since, 0.0) / period_s;
    const double phase = cycles - std::floor(cycles);  // 0 .. 1 within the period
    if (motion == SimMotion::Tap) return phase < 0.5 ? pressed : lifted(pressed);
    // Slide: a triangle 0 -> 1 -> 0 over the period, rounded to the nearest step.
    const double out_and_back = phase < 0.5 ? 2 * phase : 2 - 2 * phase;
    return slid(pressed, int(std::lround(out_and_back * kSlideSteps)));
}

MotionScenes::MotionScenes(const Contact& pressed, SimMotion motion, const Grid& grid, const LedRig& rig) {
    for (const Contact& c : motion_contacts(pressed, motion)) scenes_.emplace_back(c, render_scene(c, grid, rig));
}

const LedImages& MotionScenes::images(const Contact& contact) const {
    for (const auto& [c, images] : scenes_)
        if (c == contact) return images;
    throw std::logic_error("sim: a contact outside the motion's scenes");
}

}  // namespace sim
}  // namespace vkfuse

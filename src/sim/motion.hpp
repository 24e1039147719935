// sim/motion.hpp - a pressed object moving over time (SimMotion), and the
// scenes its motion visits, each rendered once when the object is pressed.
#pragma once
#include <utility>
#include <vector>

#include "sim/lighting.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::sim {

// Every contact `motion` visits from `pressed`, in the order of one period
// (Still: pressed alone; Tap: pressed, then lifted; Slide: 9 positions out
// and back). A frame's contact is always one of these.
std::vector<Contact> motion_contacts(const Contact& pressed, SimMotion motion);

// The contact `since` seconds after `pressed` was pressed (since < 0 counts
// as 0: a frame taken just before the press still shows it, as set_object
// promises for the next grabbed frame).
Contact contact_at(const Contact& pressed, SimMotion motion, double period_s, double since);

// The LED images of every contact of one motion, rendered up front so that
// grabbing a frame never renders.
class MotionScenes {
public:
    MotionScenes(const Contact& pressed, SimMotion motion, const Grid& grid, const LedRig& rig);
    // Throws std::logic_error for a contact the motion does not visit.
    const LedImages& images(const Contact& contact) const;

private:
    std::vector<std::pair<Contact, LedImages>> scenes_;
};

}  // namespace vkfuse::sim

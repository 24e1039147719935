// sim_record.hpp - recording a dataset from the simulated DIGIT, as
// `vkfuse sim` and `vkfuse tune` (without a DIGIT plugged in) do.
#pragma once
#include <string>
#include <vector>

#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::cli {

// "0,15" -> every r,g,b combination of the levels, r slowest. Throws
// Error(InvalidArgument) naming `option` for a malformed list or a level
// beyond the DIGIT's.
std::vector<Illumination> parse_grid(const std::string& option, const std::string& text);

// Throws Error(InvalidArgument) "<subject>: unknown object (expected ...)"
// unless the simulator knows object ("coin" is "coin-heads"'s other name).
void check_sim_object(const std::string& subject, const std::string& object);
// "coin,lego" -> the objects, each checked; errors name "<option> <object>".
std::vector<std::string> parse_sim_objects(const std::string& option, const std::string& text);
// Every object but "nothing" and the alias "coin".
std::vector<std::string> every_sim_object();

// Presses each of record.objects into a simulated DIGIT on a virtual clock
// and records it under record.grid into directory (a new, empty one), after
// the background. record.place_object is set here.
void record_simulated(const std::string& directory, SimDigitOptions sim, RecordOptions record);

}  // namespace vkfuse::cli

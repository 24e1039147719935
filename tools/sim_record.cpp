#include "sim_record.hpp"

#include <algorithm>

#include "args.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {
std::vector<Illumination> parse_grid(const std::string& option, const std::string& text) {
    std::vector<int> levels;
    const int max_level = LedLayout::digit().max_level;
    for (const std::string& v : split_list(text)) {
        const int level = parse_count(option, v);
        if (level > max_level)
            throw Error(ErrorKind::InvalidArgument,
                        option + " " + text + ": level " + v + " exceeds " + std::to_string(max_level));
        if (std::find(levels.begin(), levels.end(), level) == levels.end()) levels.push_back(level);
    }
    std::vector<Illumination> grid;
    for (int r : levels)
        for (int g : levels)
            for (int b : levels) grid.push_back(Illumination({r, g, b}));
    return grid;
}

std::vector<std::string> every_sim_object() {
    const std::vector<std::string> known = SimDigit::objects();
    std::vector<std::string> out;
    std::copy_if(known.begin(), known.end(), std::back_inserter(out),
                 [](const std::string& o) { return o != "nothing" && o != "coin"; });
    return out;
}

void check_sim_object(const std::string& subject, const std::string& object) {
    const std::vector<std::string> known = SimDigit::objects();
    // "coin" is the documented other name of "coin-heads".
    if (object == "coin" || std::find(known.begin(), known.end(), object) != known.end()) return;
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    throw Error(ErrorKind::InvalidArgument, subject + ": unknown object (expected " + list + ")");
}

std::vector<std::string> parse_sim_objects(const std::string& option, const std::string& text) {
    std::vector<std::string> out = split_list(text);
    for (const std::string& o : out) check_sim_object(option + " " + o, o);
    return out;
}

void record_simulated(const std::string& directory, SimDigitOptions sim_options, RecordOptions record) {
    sim_options.object = "nothing";
    sim_options.clock = make_virtual_clock();
    SimDigit sim(sim_options);
    DatasetWriter writer(directory, "vkfuse sim");
    record.place_object = [&](const std::string& object) { sim.set_object(object); };
    record_dataset(sim, sim_options.clock, writer, record);
    writer.finish();
}

}  // namespace vkfuse::cli

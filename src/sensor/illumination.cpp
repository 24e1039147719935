// LED layouts, illumination settings and their text form (include/vkfuse/sensor/illumination.hpp).
#include <algorithm>
#include <charconv>
#include <string>
#include <string_view>
#include <system_error>

#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse {
namespace {

[[noreturn]] void fail(std::string_view subject, std::string_view text, const std::string& problem) {
    throw Error(ErrorKind::InvalidArgument, std::string(subject) + " \"" + std::string(text) + "\": " + problem);
}

// One level: a non-negative decimal integer, nothing else (no sign, no blanks),
// so that "15, 15" and "0x0f" are rejected instead of half-read.
int parse_level(std::string_view whole, std::string_view part, std::size_t position) {
    const std::string which = "level " + std::to_string(position + 1);
    if (part.empty()) fail("illumination", whole, which + " is empty");
    int value = 0;
    const char* end = part.data() + part.size();
    auto [ptr, ec] = std::from_chars(part.data(), end, value);
    if (ptr != end || part.front() == '-' || part.front() == '+')
        fail("illumination", whole, which + " \"" + std::string(part) + "\" is not a non-negative integer");
    if (ec == std::errc::result_out_of_range) fail("illumination", whole, which + " is out of range");
    return value;
}

}  // namespace

LedLayout LedLayout::digit() { return {"DIGIT", 3, 15, {"r", "g", "b"}}; }

LedLayout LedLayout::digit360() {
    LedLayout layout{"Digit360", 24, 255, {}};
    for (int led = 0; led < 8; ++led)
        for (const char* colour : {"r", "g", "b"}) layout.names.push_back("led" + std::to_string(led) + "." + colour);
    return layout;
}

std::string Illumination::to_string() const {
    std::string out;
    for (std::size_t i = 0; i < levels_.size(); ++i) {
        if (i) out += ',';
        out += std::to_string(levels_[i]);
    }
    return out;
}

bool Illumination::is_full(const LedLayout& layout) const {
    return int(levels_.size()) == layout.channels &&
           std::all_of(levels_.begin(), levels_.end(), [&](int level) { return level == layout.max_level; });
}

void Illumination::check(const LedLayout& layout) const {
    const std::string subject = "illumination " + to_string();
    if (int(levels_.size()) != layout.channels)
        throw Error(ErrorKind::InvalidArgument, subject + ": " + std::to_string(levels_.size()) + " levels, " +
                                                    layout.model + " has " + std::to_string(layout.channels) +
                                                    " LED channels");
    for (std::size_t i = 0; i < levels_.size(); ++i) {
        const std::string name = i < layout.names.size() ? layout.names[i] : "channel " + std::to_string(i);
        if (levels_[i] < 0)
            throw Error(ErrorKind::InvalidArgument,
                        subject + ": level " + std::to_string(levels_[i]) + " of " + name + " is below 0");
        if (levels_[i] > layout.max_level)
            throw Error(ErrorKind::InvalidArgument, subject + ": level " + std::to_string(levels_[i]) + " of " +
                                                        name + " exceeds " + std::to_string(layout.max_level));
    }
}

Illumination Illumination::parse(std::string_view text) {
    if (text.empty()) fail("illumination", text, "no levels");
    std::vector<int> levels;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::size_t stop = comma == std::string_view::npos ? text.size() : comma;
        levels.push_back(parse_level(text, text.substr(start, stop - start), levels.size()));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return Illumination(std::move(levels));
}

IlluminationSequence parse_sequence(std::string_view text) {
    if (text.empty()) fail("illumination sequence", text, "no settings");
    IlluminationSequence sequence;
    std::size_t start = 0;
    while (true) {
        const std::size_t plus = text.find('+', start);
        const std::size_t stop = plus == std::string_view::npos ? text.size() : plus;
        const std::string_view part = text.substr(start, stop - start);
        try {
            sequence.push_back(Illumination::parse(part));
        } catch (const Error& e) {
            // Name the whole sequence too: "15,15,15+" should say which setting is wrong.
            fail("illumination sequence", text,
                 "setting " + std::to_string(sequence.size() + 1) + ": " + e.what());
        }
        if (plus == std::string_view::npos) break;
        if (sequence.size() == kMaxSequenceSettings)  // named by its start: the whole may be long
            fail("illumination sequence", std::string(text.substr(0, plus)) + "+...",
                 "more than " + std::to_string(kMaxSequenceSettings) + " settings in one cycle");
        start = plus + 1;
    }
    return sequence;
}

std::string to_string(const IlluminationSequence& sequence) {
    std::string out;
    for (std::size_t i = 0; i < sequence.size(); ++i) {
        if (i) out += '+';
        out += sequence[i].to_string();
    }
    return out;
}

IlluminationSequence distinct_settings(const IlluminationSequence& sequence) {
    IlluminationSequence out;
    for (const Illumination& s : sequence)
        if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
    return out;
}

}  // namespace vkfuse

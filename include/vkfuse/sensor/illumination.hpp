// vkfuse/sensor/illumination.hpp - LED settings of a sensor and the sequence used per cycle.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace vkfuse {

// The LEDs a sensor model has. DIGIT: 3 LEDs (red, green, blue), levels 0..15.
// Digit360: 8 RGB LEDs = 24 channels, 0..255. Anything else fits the same shape.
struct LedLayout {
    std::string model;
    int channels = 3;         // individually settable LED channels
    int max_level = 15;       // levels are 0..max_level
    std::vector<std::string> names;  // one per channel ("r", "g", "b")

    static LedLayout digit();     // 3 channels r, g, b; 0..15
    static LedLayout digit360();  // 24 channels led0.r .. led7.b; 0..255
};

// The level of every LED channel. DIGIT default: (15, 15, 15).
class Illumination {
public:
    Illumination() = default;
    explicit Illumination(std::vector<int> levels) : levels_(std::move(levels)) {}

    const std::vector<int>& levels() const { return levels_; }
    int level(int channel) const { return levels_.at(std::size_t(channel)); }
    // "15,15,15"
    std::string to_string() const;
    // Throws Error(InvalidArgument) naming the setting when the channel count or
    // a level does not fit layout ("illumination 16,0,0: level 16 of r exceeds 15").
    void check(const LedLayout& layout) const;
    // Every LED channel at layout's highest level: the static setting that
    // sensors without dynamic illumination keep, which a study measures against.
    bool is_full(const LedLayout& layout) const;

    // "15,15,15" -> {15, 15, 15}; throws Error(InvalidArgument) on malformed text.
    static Illumination parse(std::string_view text);

    friend bool operator==(const Illumination&, const Illumination&) = default;

private:
    std::vector<int> levels_;
};

// The ordered settings a sensor cycles through, one frame each per cycle.
using IlluminationSequence = std::vector<Illumination>;

// Settings one cycle takes at most: the paper fuses up to 5, a study's greedy
// sequences go to 12, and each setting costs a frame period per cycle, so a
// longer cycle (a DIGIT at 60 fps would fuse under 4 times a second) is a
// mistake, never a configuration.
inline constexpr std::size_t kMaxSequenceSettings = 16;

// "15,15,15+0,15,0" -> two settings; throws Error(InvalidArgument), also for
// more than kMaxSequenceSettings.
IlluminationSequence parse_sequence(std::string_view text);
std::string to_string(const IlluminationSequence& sequence);
// The sequence's settings, each once, in order of first use (those a
// background is taken under).
IlluminationSequence distinct_settings(const IlluminationSequence& sequence);

}  // namespace vkfuse

// sensor/row_profile.hpp - per-row frame means: how calibration sees a rolling
// shutter. Rows start exposing one after another, so a switch that lands
// during a frame moves the means of its later rows and leaves the earlier ones.
#pragma once
#include <vector>

#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse::sensor {

// Mean of every row over its pixels and channels, in 8-bit levels.
using RowProfile = std::vector<double>;
RowProfile row_profile(const Frame& frame);

// Largest |a_i - b_i| (same length).
double max_row_difference(const RowProfile& a, const RowProfile& b);

enum class Lighting { Old, New, Mixed };

// Compares a frame's rows with the steady profiles of the old and the new
// setting. Only rows that the switch moves by at least min_change levels take
// part (rows[i]); each gets alpha = (p - old) / (new - old). New: every alpha
// within tolerance of 1; Old: every alpha within tolerance of 0; anything else
// is Mixed (two settings, or a camera still settling on one).
class LightingJudge {
public:
    LightingJudge(RowProfile old_profile, RowProfile new_profile, double tolerance, double min_change);
    Lighting judge(const RowProfile& frame) const;
    // Fraction of the rows that respond to the switch.
    double responsive_fraction() const;

private:
    RowProfile old_, new_;
    std::vector<std::size_t> rows_;
    double tolerance_;
};

}  // namespace vkfuse::sensor

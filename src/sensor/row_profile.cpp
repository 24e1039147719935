#include "sensor/row_profile.hpp"

#include <algorithm>
#include <cmath>

namespace vkfuse::sensor {

RowProfile row_profile(const Frame& frame) {
    RowProfile rows(std::size_t(frame.height), 0.0);
    const std::size_t row_values = std::size_t(frame.width) * 3;
    for (std::size_t y = 0; y < rows.size(); ++y) {
        const std::uint8_t* p = frame.pixels.data() + y * row_values;
        std::uint64_t sum = 0;  // exact: at most 255 * 3 * width per row
        for (std::size_t i = 0; i < row_values; ++i) sum += p[i];
        rows[y] = double(sum) / double(row_values);
    }
    return rows;
}

double max_row_difference(const RowProfile& a, const RowProfile& b) {
    double worst = 0;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    return worst;
}

LightingJudge::LightingJudge(RowProfile old_profile, RowProfile new_profile, double tolerance, double min_change)
    : old_(std::move(old_profile)), new_(std::move(new_profile)), tolerance_(tolerance) {
    for (std::size_t i = 0; i < old_.size() && i < new_.size(); ++i)
        if (std::abs(new_[i] - old_[i]) >= min_change) rows_.push_back(i);
}

Lighting LightingJudge::judge(const RowProfile& frame) const {
    bool all_new = true, all_old = true;
    for (std::size_t i : rows_) {
        const double alpha = (frame[i] - old_[i]) / (new_[i] - old_[i]);
        // Both ways: a camera still settling after a switch over- or undershoots.
        all_new = all_new && std::abs(alpha - 1.0) <= tolerance_;
        all_old = all_old && std::abs(alpha) <= tolerance_;
    }
    if (rows_.empty() || (!all_new && !all_old)) return Lighting::Mixed;
    return all_new ? Lighting::New : Lighting::Old;
}

double LightingJudge::responsive_fraction() const {
    return old_.empty() ? 0.0 : double(rows_.size()) / double(old_.size());
}

}  // namespace vkfuse::sensor

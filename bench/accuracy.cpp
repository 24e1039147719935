#include "accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "vkfuse/core/reference.hpp"

namespace vkfuse::bench {

std::vector<int> checked_sensors(int sensors) {
    std::vector<int> out;
    for (int i = 0; i < 4; ++i) out.push_back(int((long long)(sensors - 1) * i / 3));
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::vector<Expected> expected_results(const Inputs& in, const FusionSpec& spec) {
    std::map<int, std::size_t> by_scene;  // scene -> index of its result in out
    std::vector<Expected> out;
    for (int sensor : checked_sensors(in.sensors())) {
        if (auto it = by_scene.find(in.scene_of(sensor)); it != by_scene.end()) {
            Expected copy = out[it->second];
            copy.sensor = sensor;
            out.push_back(std::move(copy));
            continue;
        }
        std::vector<ImageD> frames;
        for (int k = 0; k < in.frames(); ++k) frames.push_back(convert<double>(in.frame(sensor, k)));
        Expected e;
        e.sensor = sensor;
        e.fused = fuse_reference(frames, spec);
        const ImageD background = convert<double>(in.background(sensor));
        e.metrics = metrics_reference(e.fused, &background);
        by_scene[in.scene_of(sensor)] = out.size();
        out.push_back(std::move(e));
    }
    return out;
}

namespace {

// Relative error; against a reference of exactly 0 the absolute error is all
// there is. NaN counts as infinitely wrong (max() would drop it).
double relative(double got, double want) {
    const double d = std::abs(got - want);
    if (std::isnan(d)) return std::numeric_limits<double>::infinity();
    return want == 0 ? d : d / std::abs(want);
}

template <class T>
void accumulate(FusedError& acc, const BasicImage<T>& got, const ImageD& want) {
    if (got.height != want.height || got.width != want.width || got.channels != want.channels)
        throw std::runtime_error("fused image is " + std::to_string(got.height) + "x" + std::to_string(got.width) + "x" +
                                 std::to_string(got.channels) + ", the reference " + std::to_string(want.height) + "x" +
                                 std::to_string(want.width) + "x" + std::to_string(want.channels));
    for (std::size_t i = 0; i < want.data.size(); ++i) {
        const double d = std::abs(double(got.data[i]) - want.data[i]);
        // A NaN must not hide behind max(): count it as infinitely wrong.
        const double e = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
        acc.max_abs = std::max(acc.max_abs, e);
        acc.sum_abs += e;
        acc.over_tolerance += e > kFusedTolerance;
    }
    acc.samples += want.data.size();
}

}  // namespace

void FusedError::add(const Image& got, const ImageD& want) { accumulate(*this, got, want); }
void FusedError::add(const ImageD& got, const ImageD& want) { accumulate(*this, got, want); }

void MetricError::add(const Metrics& got, const Metrics& want) {
    sharpness = std::max(sharpness, relative(got.sharpness, want.sharpness));
    contrast = std::max(contrast, relative(got.contrast, want.contrast));
    if (got.background_diff && want.background_diff)
        background_diff = std::max(background_diff, relative(*got.background_diff, *want.background_diff));
}

double MetricError::worst() const { return std::max({sharpness, contrast, background_diff}); }

}  // namespace vkfuse::bench

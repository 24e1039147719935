// study_dataset.hpp - a small synthetic dataset for `vkfuse study` tests:
// 96x128 frames, per object a frame under each setting of a grid and a
// background under each, written by the library's DatasetWriter.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::test {

struct StudyDatasetSpec {
    std::vector<std::string> objects = {"ridge", "dots"};
    std::vector<int> levels = {0, 15};  // every r,g,b combination of these
    int backgrounds_per_setting = 2;
    bool with_static = true;            // keep (15,15,15)
};

// A setting lights each channel of the gel in proportion to its level; the
// object adds relief (a structured image per object) the light picks out,
// each background frame its own small noise.
inline std::vector<Illumination> study_grid(const StudyDatasetSpec& spec) {
    std::vector<Illumination> grid;
    for (int r : spec.levels)
        for (int g : spec.levels)
            for (int b : spec.levels)
                if (spec.with_static || !(r == 15 && g == 15 && b == 15)) grid.push_back(Illumination({r, g, b}));
    return grid;
}

inline Frame study_frame(const Illumination& s, const ImageD* relief, std::uint32_t noise_seed) {
    constexpr int kH = 96, kW = 128;
    const ImageD gel = structured_image(kH, kW, 3, 7);
    const ImageD noise = random_image(kH, kW, 3, noise_seed);
    Frame f;
    f.height = kH;
    f.width = kW;
    f.pixels.resize(std::size_t(kH) * kW * 3);
    for (std::size_t i = 0; i < f.pixels.size(); ++i) {
        const double light = 0.15 + 0.85 * s.level(int(i % 3)) / 15.0;
        const double v = light * (0.35 + 0.3 * gel.data[i] + (relief ? 0.3 * relief->data[i] : 0.0)) +
                         0.01 * noise.data[i];
        f.pixels[i] = std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255));
    }
    return f;
}

inline void write_study_dataset(const std::string& dir, const StudyDatasetSpec& spec = {}) {
    DatasetWriter writer(dir, "test");
    SensorInfo info;
    info.model = "dataset";
    info.serial = "STUDY-1";
    info.width = 128;
    info.height = 96;
    info.fps = 30;
    info.leds = LedLayout::digit();
    const int sensor = writer.add_sensor(info);
    const std::vector<Illumination> grid = study_grid(spec);
    std::uint32_t seed = 100;
    for (const Illumination& s : grid)
        for (int k = 0; k < spec.backgrounds_per_setting; ++k)
            writer.add_frame(sensor, "nothing", true, study_frame(s, nullptr, seed++), s);
    for (std::size_t o = 0; o < spec.objects.size(); ++o) {
        const ImageD relief = structured_image(96, 128, 3, 40 + std::uint32_t(o));
        for (const Illumination& s : grid) writer.add_frame(sensor, spec.objects[o], false, study_frame(s, &relief, seed++), s);
    }
    writer.finish();
}

}  // namespace vkfuse::test

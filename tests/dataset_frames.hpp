// dataset_frames.hpp - the small sensor and patterned frames the dataset
// tests write: 6x4 RGB, distinct per index and seed, with timestamps that
// are not exact in binary (they must survive every form a dataset takes).
#pragma once
#include <cstdint>
#include <string>

#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse::test {

inline SensorInfo small_sensor(const std::string& serial) { return {"test", serial, 6, 4, 60.0, LedLayout::digit()}; }

inline Frame pattern_frame(std::uint64_t index, int seed) {
    Frame f;
    f.index = index;
    f.timestamp = 0.1 + double(index) / 60.0;
    f.height = 4;
    f.width = 6;
    f.pixels.resize(4 * 6 * 3);
    for (std::size_t i = 0; i < f.pixels.size(); ++i)
        f.pixels[i] = std::uint8_t((i * 37 + std::size_t(seed) * 11) % 256);
    return f;
}

}  // namespace vkfuse::test

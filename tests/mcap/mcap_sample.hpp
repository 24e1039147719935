// mcap_sample.hpp - one MCAP file's worth of messages, the same every time:
// two schemas, three channels, messages of many sizes (empty to a few KiB)
// across several chunks, with distinct log times. The unit test and the
// independent reader's test (tests/mcap) write it and compare what comes back
// with sample_lines(): "topic sequence log_time publish_time length bytesum".
#pragma once
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "io/mcap_writer.hpp"

namespace vkfuse::test {

struct SampleMessage {
    std::string topic;
    std::uint16_t channel;
    std::uint32_t sequence;
    std::uint64_t log_time, publish_time;
    std::vector<std::uint8_t> data;
};

inline std::vector<SampleMessage> sample_messages() {
    std::vector<SampleMessage> out;
    const char* topics[] = {"/vkfuse/SIM-0001/fused", "/vkfuse/SIM-0001/metrics", "/vkfuse/rig"};
    std::uint32_t state = 12345;
    for (std::uint32_t i = 0; i < 120; ++i) {
        const std::uint16_t channel = std::uint16_t(i % 3 + 1);
        std::vector<std::uint8_t> data((i * 37) % 3000);
        for (std::uint8_t& b : data) b = std::uint8_t((state = state * 1103515245u + 12345u) >> 24);
        out.push_back({topics[channel - 1], channel, i / 3, 1'700'000'000'000'000'000ull + i * 16'666'667ull,
                       1'700'000'000'000'000'000ull + i * 16'666'667ull + 1000, std::move(data)});
    }
    return out;
}

// Writes the sample through w; chunk_bytes small enough gives many chunks.
inline void write_sample(io::mcap::Writer& w) {
    const std::string image = "uint32 height\nuint32 width\nstring encoding\nuint8[] data\n";
    const std::string json = R"({"type": "object"})";
    const auto s1 = w.add_schema("sensor_msgs/msg/Image", "ros2msg",
                                 {reinterpret_cast<const std::uint8_t*>(image.data()), image.size()});
    const auto s2 = w.add_schema("vkfuse.Metrics", "jsonschema",
                                 {reinterpret_cast<const std::uint8_t*>(json.data()), json.size()});
    w.add_channel(s1, "/vkfuse/SIM-0001/fused", "cdr", {{"offered_qos_profiles", ""}});
    w.add_channel(s2, "/vkfuse/SIM-0001/metrics", "json");
    w.add_channel(s2, "/vkfuse/rig", "json", {{"sensors", "1"}, {"method", "wavelet"}});
    for (const SampleMessage& m : sample_messages()) w.write(m.channel, m.sequence, m.log_time, m.publish_time, m.data);
    w.finish();
}

inline std::string sample_lines() {
    std::string out;
    for (const SampleMessage& m : sample_messages()) {
        const std::uint32_t sum = std::accumulate(m.data.begin(), m.data.end(), std::uint32_t(0));
        out += m.topic + " " + std::to_string(m.sequence) + " " + std::to_string(m.log_time) + " " +
               std::to_string(m.publish_time) + " " + std::to_string(m.data.size()) + " " + std::to_string(sum) + "\n";
    }
    return out;
}

}  // namespace vkfuse::test

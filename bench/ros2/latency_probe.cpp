// vkfuse-ros2-probe: a ROS 2 subscriber that measures what a fusion host
// delivers. It hears the fusing rigs' /vkfuse/rig and subscribes to every
// sensor's /vkfuse/<token>/fused. Once --sensors readers are matched to
// their publishers it prints "ready" on stderr and begins: for each image
// stamped after that it takes its age on arrival (system clock now -
// header.stamp: the capture time, as the capture host dated it). --seconds
// after the first such image it prints one JSON object: per sensor the
// images and their rate (images between its first and last arrival over
// that span), the slowest sensor's rate, the ages' p50, p99 and max in ms
// over all images, and the same over the images stamped --settle s or more
// after the first (the rig past its first cycles' start-up). With
// VKFUSE_PROBE_TRACE=FILE it writes each image's serial, stamp and age there.
// Used by tools/bench_ros2.sh, which starts the capture host once "ready" is
// said, so neither discovery nor the capture host's start-up is measured.
//
//   vkfuse-ros2-probe --ros-domain N --sensors N --seconds S [--settle S]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "ros2/dds_entities.hpp"
#include "sensor_msgs.h"
#include "vkfuse/ros2/publisher.hpp"
#include "vkfuse_msgs.h"

using namespace vkfuse::ros2;
using Clock = std::chrono::steady_clock;

namespace {

double system_seconds() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
    int domain = 0;
    double seconds = 10;
    std::size_t sensors = 1;
    double settle = 0;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--ros-domain")) domain = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--sensors")) sensors = std::size_t(std::atoi(argv[i + 1]));
        else if (!std::strcmp(argv[i], "--settle")) settle = std::atof(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--seconds")) seconds = std::atof(argv[i + 1]);
        else {
            std::fprintf(stderr, "usage: vkfuse-ros2-probe --ros-domain N --sensors N --seconds S [--settle S]\n");
            return 2;
        }
    }
    FILE* trace = std::getenv("VKFUSE_PROBE_TRACE") ? std::fopen(std::getenv("VKFUSE_PROBE_TRACE"), "w") : nullptr;
    try {
        const DdsEntity participant = make_participant(domain);
        const DdsEntity rig = make_reader(participant, vkfuse_msgs_msg_dds__RigDescription__desc, "/vkfuse/rig",
                                          TopicQos::reader(16));
        std::map<std::string, DdsEntity> fused;  // by serial
        struct Heard {
            std::size_t images = 0;
            double first = 0, last = 0;  // arrivals
        };
        std::map<std::string, Heard> heard;
        std::vector<std::pair<double, double>> ages;  // stamp, age in ms
        // Until every sensor's reader is matched, nothing is measured; then
        // until --seconds after the first image.
        std::optional<double> begun;
        bool first_image = false;
        Clock::time_point end = Clock::now() + std::chrono::seconds(120);  // to be heard of, and an image
        while (Clock::now() < end) {
            if (const LoanedSample<vkfuse_msgs_msg_dds__RigDescription_> sample(rig); sample.any()) {
                const auto& d = sample.message();
                if (sample.valid() && d.fused)
                    for (std::uint32_t i = 0; i < d.sensors._length; ++i) {
                        const std::string serial = d.sensors._buffer[i].serial;
                        if (!fused.count(serial))
                            fused.emplace(serial, make_reader(participant, sensor_msgs_msg_dds__Image__desc,
                                                              "/vkfuse/" + topic_token(serial) + "/fused",
                                                              TopicQos::reader(8)));
                    }
            }
            if (!begun) {
                std::size_t matched = 0;
                for (auto& [serial, reader] : fused) {
                    dds_subscription_matched_status_t status{};
                    if (dds_get_subscription_matched_status(reader.get(), &status) == DDS_RETCODE_OK &&
                        status.current_count > 0)
                        ++matched;
                }
                if (matched >= sensors) {
                    begun = system_seconds();
                    end = Clock::now() + std::chrono::seconds(120);
                    std::fprintf(stderr, "ready\n");
                }
            }
            bool any = false;
            for (auto& [serial, reader] : fused) {
                for (;;) {
                    const LoanedSample<sensor_msgs_msg_dds__Image_> sample(reader);
                    if (!sample.any()) break;
                    any = true;
                    const double now = system_seconds();
                    const auto& stamp_msg = sample.message().header.stamp;
                    const double stamp = double(stamp_msg.sec) + double(stamp_msg.nanosec) * 1e-9;
                    if (!sample.valid() || !begun || stamp < *begun) continue;
                    if (!first_image) {
                        first_image = true;
                        end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
                    }
                    ages.emplace_back(stamp, (now - stamp) * 1e3);
                    if (trace) std::fprintf(trace, "%s %.6f %.3f\n", serial.c_str(), stamp, (now - stamp) * 1e3);
                    Heard& h = heard[serial];
                    if (h.images++ == 0) h.first = now;
                    h.last = now;
                }
            }
            if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        std::string per_sensor;
        double slowest = heard.size() < sensors ? 0 : 1e9;
        for (const auto& [serial, h] : heard) {
            const double fps = h.images > 1 && h.last > h.first ? double(h.images - 1) / (h.last - h.first) : 0;
            slowest = std::min(slowest, fps);
            char text[160];
            std::snprintf(text, sizeof text, "%s\"%s\": {\"images\": %zu, \"fps\": %.2f}", per_sensor.empty() ? "" : ", ",
                          serial.c_str(), h.images, fps);
            per_sensor += text;
        }
        // All ages, and those of images stamped --settle s or more after the
        // first: the rig in its stride, past the first cycles' start-up.
        std::vector<double> all, settled;
        const double first_stamp =
            ages.empty() ? 0 : std::min_element(ages.begin(), ages.end())->first;
        for (const auto& [stamp, age] : ages) {
            all.push_back(age);
            if (stamp >= first_stamp + settle) settled.push_back(age);
        }
        auto summary = [](const std::vector<double>& v) {
            char text[160];
            std::snprintf(text, sizeof text, "{\"images\": %zu, \"p50\": %.2f, \"p99\": %.2f, \"max\": %.2f}", v.size(),
                          percentile(v, 0.5), percentile(v, 0.99), percentile(v, 1.0));
            return std::string(text);
        };
        std::printf("{\"seconds\": %g, \"sensors\": {%s}, \"sensors_heard\": %zu, \"slowest_fps\": %.2f, "
                    "\"age_ms\": %s, \"settle_s\": %g, \"age_ms_settled\": %s}\n",
                    seconds, per_sensor.c_str(), heard.size(), heard.empty() ? 0.0 : slowest, summary(all).c_str(), settle,
                    summary(settled).c_str());
        if (!begun) {
            std::fprintf(stderr, "vkfuse-ros2-probe: fewer than %zu sensors' fused images heard of\n", sensors);
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkfuse-ros2-probe: %s\n", e.what());
        return 1;
    }
}

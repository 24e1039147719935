// vkfuse-ros2-probe: a ROS 2 subscriber that measures what a fusion host
// delivers. It hears the fusing rigs' /vkfuse/rig, subscribes to every
// sensor's /vkfuse/<token>/fused, and for each image stamped after it began
// takes its age on arrival (system clock now - header.stamp: the capture
// time, as the capture host dated it). After --seconds it prints one JSON
// object: per sensor the images and their rate, and the ages' p50, p99 and
// max in ms over all of them. Used by tools/bench_ros2.sh.
//
//   vkfuse-ros2-probe --ros-domain N --seconds S
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
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
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--ros-domain")) domain = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--seconds")) seconds = std::atof(argv[i + 1]);
        else {
            std::fprintf(stderr, "usage: vkfuse-ros2-probe --ros-domain N --seconds S\n");
            return 2;
        }
    }
    try {
        const DdsEntity participant = make_participant(domain);
        const DdsEntity rig = make_reader(participant, vkfuse_msgs_msg_dds__RigDescription__desc, "/vkfuse/rig",
                                          TopicQos::reader(16));
        std::map<std::string, DdsEntity> fused;  // by serial
        std::map<std::string, std::size_t> images;
        std::vector<double> ages;
        const double begun = system_seconds();
        const auto end = Clock::now() + std::chrono::duration<double>(seconds);
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
            bool any = false;
            for (auto& [serial, reader] : fused) {
                for (;;) {
                    const LoanedSample<sensor_msgs_msg_dds__Image_> sample(reader);
                    if (!sample.any()) break;
                    const double now = system_seconds();
                    const auto& stamp_msg = sample.message().header.stamp;
                    const double stamp = double(stamp_msg.sec) + double(stamp_msg.nanosec) * 1e-9;
                    if (sample.valid() && stamp >= begun) {
                        ages.push_back((now - stamp) * 1e3);
                        ++images[serial];
                        any = true;
                    }
                }
            }
            if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        std::string per_sensor;
        for (const auto& [serial, n] : images)
            per_sensor += (per_sensor.empty() ? "" : ", ") + ("\"" + serial + "\": ") + std::to_string(n);
        std::printf("{\"seconds\": %g, \"images\": {%s}, \"images_per_s_per_sensor\": %.3f, "
                    "\"age_ms\": {\"p50\": %.2f, \"p99\": %.2f, \"max\": %.2f}}\n",
                    seconds, per_sensor.c_str(),
                    images.empty() ? 0.0 : double(ages.size()) / seconds / double(images.size()),
                    percentile(ages, 0.5), percentile(ages, 0.99), percentile(ages, 1.0));
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkfuse-ros2-probe: %s\n", e.what());
        return 1;
    }
}

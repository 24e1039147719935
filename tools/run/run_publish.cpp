#include "run/run_publish.hpp"

#include <chrono>
#include <cstdio>
#include <thread>

#ifdef VKFUSE_WITH_ROS2
#include "vkfuse/ros2/publisher.hpp"
#endif

namespace vkfuse::cli {

#ifdef VKFUSE_WITH_ROS2
namespace {

class Ros2Publisher : public RunPublisher {
public:
    Ros2Publisher(const RunOptions& o, const std::vector<RigSensor>& sensors) : sensors_(sensors), wait_s_(o.publish_wait_s) {
        ros2::RigTopics topics;
        for (const RigSensor& s : sensors) topics.sensors.push_back(s.sensor->info());
        topics.sequence = o.sequence;
        topics.fusion = o.fusion;
        topics.metrics = o.metrics;
        topics.skip = o.skip;
        topics.background_frames = o.background_frames;
        topics.fused = !o.capture_only;
        // A frame's capture time on the system clock: its age on the
        // sensor's own clock, before now (a sensor without a clock: now).
        ros2::CaptureTime capture_time = [clocks = sensors](std::size_t i, double timestamp) {
            const auto now = std::chrono::system_clock::now();
            if (i >= clocks.size() || !clocks[i].clock) return now;
            const double age = std::max(0.0, clocks[i].clock->now() - timestamp);
            return now - std::chrono::duration_cast<std::chrono::system_clock::duration>(std::chrono::duration<double>(age));
        };
        publisher_.emplace(topics, ros2::PublisherOptions{o.ros_domain, o.publish_encoding, o.publish_frames},
                           std::move(capture_time));
    }

    void wait_for_subscribers() override {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s_);
        for (;;) {
            bool all = true;
            for (std::size_t i = 0; i < sensors_.size() && all; ++i) all = publisher_->has_subscribers(i);
            if (all) return;
            if (std::chrono::steady_clock::now() >= deadline) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        if (wait_s_ > 0)
            std::fprintf(stderr, "vkfuse run: --publish-wait %g: not every sensor's topics have a subscriber; "
                                 "publishing anyway\n", wait_s_);
    }

    void publish(const CycleResult& cycle) override { publisher_->publish(cycle); }

    void publish_background(std::size_t sensor, const Illumination& setting, const std::vector<Frame>& frames) override {
        publisher_->publish_background(sensor, setting, frames);
    }

private:
    std::vector<RigSensor> sensors_;
    double wait_s_;
    std::optional<ros2::RigPublisher> publisher_;
};

}  // namespace

std::unique_ptr<RunPublisher> RunPublisher::make(const RunOptions& o, const std::vector<RigSensor>& sensors) {
    if (!o.publish_ros2) return nullptr;
    return std::make_unique<Ros2Publisher>(o, sensors);
}
#else
// run_options.cpp refused --publish already.
std::unique_ptr<RunPublisher> RunPublisher::make(const RunOptions&, const std::vector<RigSensor>&) { return nullptr; }
#endif

}  // namespace vkfuse::cli

#include "run_publish.hpp"

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
        publisher_.emplace(topics, ros2::PublisherOptions{o.ros_domain, o.publish_encoding});
    }

    void wait_for_subscribers() override {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s_);
        for (;;) {
            bool all = true;
            for (std::size_t i = 0; i < sensors_.size() && all; ++i)
                all = publisher_->metrics_subscribers(i) > 0 && publisher_->fused_subscribers(i) > 0;
            if (all) return;
            if (std::chrono::steady_clock::now() >= deadline) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        if (wait_s_ > 0)
            std::fprintf(stderr, "vkfuse run: --publish-wait %g: not every sensor's fused and metrics topics have a subscriber; "
                                 "publishing anyway\n", wait_s_);
    }

    // header.stamp: when the cycle's first frame was exposed, on the system
    // clock: its age on the sensor's own clock, before now.
    void publish(const CycleResult& cycle) override {
        const auto now = std::chrono::system_clock::now();
        std::vector<std::chrono::system_clock::time_point> captured(cycle.sensors.size(), now);
        for (std::size_t i = 0; i < cycle.sensors.size() && i < sensors_.size(); ++i) {
            const SensorCycle& s = cycle.sensors[i];
            if (s.status != SensorStatus::Ok || s.frames.empty() || !sensors_[i].clock) continue;
            const double age = std::max(0.0, sensors_[i].clock->now() - s.frames.front().timestamp);
            captured[i] = now - std::chrono::duration_cast<std::chrono::system_clock::duration>(
                                    std::chrono::duration<double>(age));
        }
        publisher_->publish(cycle, captured);
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

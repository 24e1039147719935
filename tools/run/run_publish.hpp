// run_publish.hpp - `vkfuse run --publish ros2`: every cycle of the rig also
// on ROS 2's wire, through vkfuse::ros2 (a vkfuse built without it refuses
// the option while parsing: run_options.cpp).
#pragma once
#include <memory>
#include <vector>

#include "run/run_options.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::cli {

class RunPublisher {
public:
    // What o asks for, for these sensors (their clocks date each cycle):
    // null without --publish. Joins the ROS 2 domain now, so that
    // subscribers find it while the rig starts.
    static std::unique_ptr<RunPublisher> make(const RunOptions& o, const std::vector<RigSensor>& sensors);
    virtual ~RunPublisher() = default;
    // Before the first cycle: waits until every topic each sensor publishes
    // per cycle has a subscriber, or --publish-wait's seconds pass (one line
    // then says so).
    virtual void wait_for_subscribers() = 0;
    virtual void publish(const CycleResult& cycle) = 0;
    // A sensor's background frames of one setting (RigConfig::on_background):
    // published with --publish-frames once all its settings are in.
    virtual void publish_background(std::size_t sensor, const Illumination& setting, const std::vector<Frame>& frames) = 0;
};

}  // namespace vkfuse::cli

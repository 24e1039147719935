// run_publish.hpp - `vkfuse run --publish ros2`: every cycle of the rig also
// on ROS 2's wire, through vkfuse::ros2 (a vkfuse built without it refuses
// the option while parsing: run_options.cpp).
#pragma once
#include <memory>
#include <vector>

#include "run_options.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::cli {

class RunPublisher {
public:
    // What o asks for, for these sensors (their clocks date each cycle):
    // null without --publish. Joins the ROS 2 domain now, so that
    // subscribers find it while the rig starts.
    static std::unique_ptr<RunPublisher> make(const RunOptions& o, const std::vector<RigSensor>& sensors);
    virtual ~RunPublisher() = default;
    // Before the first cycle: waits until every sensor's fused and metrics
    // topics have a subscriber, or --publish-wait's seconds pass (one line
    // then says so).
    virtual void wait_for_subscribers() = 0;
    virtual void publish(const CycleResult& cycle) = 0;
};

}  // namespace vkfuse::cli

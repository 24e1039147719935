// One reusable command buffer whose recorded work is timed: by timestamp
// queries around it when the queue has them, else by the host clock around
// submit + wait. Device measurements (copy bandwidth, kernel access costs)
// share it.
#pragma once
#include <functional>

#include "vk/engine/command_slot.hpp"

namespace vkfuse::vk {

class TimedCommands {
public:
    explicit TimedCommands(Context::Impl& ctx);

    // Replaces the recorded work: body(cmd) between two timestamps.
    void record(const std::function<void(VkCommandBuffer)>& body);
    // Submits what was recorded, waits, and returns the seconds it took.
    double run();
    // The median seconds of `repeats` runs after one warm-up run.
    double median_of(int repeats);
    bool device_timed() const { return slot_.queries() != VK_NULL_HANDLE; }

private:
    Context::Impl& ctx_;
    CommandSlot slot_;
};

}  // namespace vkfuse::vk

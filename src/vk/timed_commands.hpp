// One reusable command buffer whose recorded work is timed: by timestamp
// queries around it when the queue has them, else by the host clock around
// submit + wait. Device measurements (copy bandwidth, kernel access costs)
// share it.
#pragma once
#include <functional>

#include "vk/context_impl.hpp"

namespace vkfuse::vk {

class TimedCommands {
public:
    explicit TimedCommands(Context::Impl& ctx);
    ~TimedCommands();
    TimedCommands(const TimedCommands&) = delete;
    TimedCommands& operator=(const TimedCommands&) = delete;

    // Replaces the recorded work: body(cmd) between two timestamps.
    void record(const std::function<void(VkCommandBuffer)>& body);
    // Submits what was recorded, waits, and returns the seconds it took.
    double run();
    // The median seconds of `repeats` runs after one warm-up run.
    double median_of(int repeats);
    bool device_timed() const { return queries_ != VK_NULL_HANDLE; }

private:
    Context::Impl& ctx_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkQueryPool queries_ = VK_NULL_HANDLE;

    void release();
};

}  // namespace vkfuse::vk

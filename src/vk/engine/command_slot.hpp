// One primary command buffer with its pool, a fence and, when asked for, a
// timestamp query pool, or a secondary command buffer and a timeline semaphore:
// what every vkfuse submission needs (a Plan's cycle, the timed device
// measurements). Everything is released in any case; a submit whose wait
// failed (device lost) is waited out before release.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "vk/engine/context_impl.hpp"

namespace vkfuse::vk {

class CommandSlot {
public:
    // timestamp_queries: size of the query pool, 0 for none. secondary: the
    // work is recorded into a secondary command buffer (recording_target()),
    // which the primary executes and callers' command buffers may execute
    // too (vkfuse::record).
    CommandSlot(Context::Impl& ctx, std::uint32_t timestamp_queries, bool secondary = false);
    ~CommandSlot();
    CommandSlot(const CommandSlot&) = delete;
    CommandSlot& operator=(const CommandSlot&) = delete;

    // The buffer may be recorded again (its pool allows the implicit reset).
    VkCommandBuffer cmd() const { return cmd_; }
    VkQueryPool queries() const { return queries_; }  // VK_NULL_HANDLE without timestamps
    std::uint32_t query_count() const { return query_count_; }  // its size (0 without)
    VkCommandBuffer secondary() const { return secondary_; }  // VK_NULL_HANDLE unless asked for
    // Where the work is recorded: the secondary buffer where there is one.
    VkCommandBuffer recording_target() const { return secondary_ ? secondary_ : cmd_; }
    // Once the secondary is recorded: the primary that executes it.
    void record_primary();

    void submit();  // the recorded buffer, under the context's queue lock
    // The same after `waits`; its completion sets timeline() to the value
    // returned (1, 2, ...). Only a slot with a secondary buffer has the
    // timeline (it is made for callers: vkfuse::submit), and its every
    // submit signals it and is waited for through it; other slots use their
    // fence. No submit has both: lavapipe's fence wait was seen to hang now
    // and then under load when a submit signalled a timeline too.
    std::uint64_t submit_signalling(std::span<const SemaphoreWait> waits);
    VkSemaphore timeline() const { return timeline_; }
    void wait();    // for the fence of the last submit
    void submit_and_wait() {
        submit();
        wait();
    }
    // The first `count` timestamps of the last submit, in ticks, made
    // non-decreasing: a counter of fewer than 64 valid bits that wrapped
    // between two of them still gives their true difference.
    std::vector<std::uint64_t> timestamps(std::uint32_t count) const;

private:
    Context::Impl& ctx_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    std::uint32_t query_count_ = 0;
    VkCommandBuffer secondary_ = VK_NULL_HANDLE;
    VkSemaphore timeline_ = VK_NULL_HANDLE;
    std::uint64_t timeline_value_ = 0;  // signalled by the last submit
    bool in_flight_ = false;  // submitted and not yet waited for

    void release();
    void wait_for_device() const;  // the timeline's last value, or the fence
};

}  // namespace vkfuse::vk

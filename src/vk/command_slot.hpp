// One primary command buffer with its pool, a fence and, when asked for, a
// timestamp query pool: what every vkfuse submission needs (a Plan's cycle,
// the timed device measurements). Everything is released in any case; a
// submit whose wait failed (device lost) is waited out before release.
#pragma once
#include <cstdint>
#include <vector>

#include "vk/context_impl.hpp"

namespace vkfuse::vk {

class CommandSlot {
public:
    // timestamp_queries: size of the query pool, 0 for none.
    CommandSlot(Context::Impl& ctx, std::uint32_t timestamp_queries);
    ~CommandSlot();
    CommandSlot(const CommandSlot&) = delete;
    CommandSlot& operator=(const CommandSlot&) = delete;

    // The buffer may be recorded again (its pool allows the implicit reset).
    VkCommandBuffer cmd() const { return cmd_; }
    VkQueryPool queries() const { return queries_; }  // VK_NULL_HANDLE without timestamps

    void submit();  // the recorded buffer, under the context's queue lock
    void wait();    // for the fence of the last submit
    void submit_and_wait() {
        submit();
        wait();
    }
    // The first `count` timestamps of the last submit, in ticks.
    std::vector<std::uint64_t> timestamps(std::uint32_t count) const;

private:
    Context::Impl& ctx_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    bool in_flight_ = false;  // submitted and not yet waited for

    void release();
};

}  // namespace vkfuse::vk

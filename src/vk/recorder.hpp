// Records a plan's dispatches into one command buffer: a barrier between
// dependent dispatches and, when profiling, a timestamp after each stage.
#pragma once
#include <string>
#include <vector>

#include "vk/context_impl.hpp"
#include "vk/push_constants.hpp"

namespace vkfuse::vk {

class Recorder {
public:
    static constexpr std::uint32_t kMaxTimestamps = 512;

    // queries may be VK_NULL_HANDLE (no profiling).
    Recorder(Context::Impl& ctx, VkCommandBuffer cmd, VkQueryPool queries);

    // Records shader with push constants over groups (x, y, z). Everything the
    // previous dispatches wrote is visible to it.
    void dispatch(const std::string& shader, const PushConstants& push, std::uint32_t gx, std::uint32_t gy,
                  std::uint32_t gz);
    // Closes the stage begun after the previous mark: its GPU time is reported under name.
    void mark(const std::string& name);
    void finish();  // makes shader writes visible to the host and ends the buffer

    const std::vector<std::string>& stage_names() const { return names_; }

private:
    Context::Impl& ctx_;
    VkCommandBuffer cmd_;
    VkQueryPool queries_;
    bool first_ = true;
    std::vector<std::string> names_;

    void barrier(VkPipelineStageFlags src, VkAccessFlags src_access, VkPipelineStageFlags dst,
                 VkAccessFlags dst_access);
};

// Dispatch group count covering n items with groups of size per_group.
inline std::uint32_t groups(std::uint64_t n, std::uint32_t per_group) {
    return std::uint32_t((n + per_group - 1) / per_group);
}

}  // namespace vkfuse::vk

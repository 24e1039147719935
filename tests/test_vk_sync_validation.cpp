// The tests' Vulkan context runs the validation layer's synchronization
// validation: lavapipe runs a submit's commands in order, so a missing
// barrier passes there and races on a GPU; only this layer shows it. A
// deliberate hazard (two writes to one buffer, no barrier between) must be
// reported, else every GPU test's silence would prove nothing about barriers.
#include <gtest/gtest.h>

#include <algorithm>

#include "vk/engine/buffer.hpp"
#include "vk/engine/context_impl.hpp"
#include "vk/engine/timed_commands.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

TEST(VulkanSyncValidation, AMissingBarrierIsReportedAsAHazard) {
    SKIP_WITHOUT_VALIDATION();
    Context& context = shared_context();
    auto& ctx = vk::ContextAccess::of(context);
    vk::Buffer buffer(ctx, 4096, vk::MemoryUse::Device);
    std::size_t before = 0;
    {
        std::lock_guard lock(validation_log().mutex);
        before = validation_log().messages.size();
    }
    vk::TimedCommands job(ctx);
    job.record([&](VkCommandBuffer cmd) {
        ctx.api->vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 1u);
        ctx.api->vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 2u);  // no barrier: write after write
    });
    job.run();
    std::lock_guard lock(validation_log().mutex);
    auto& all = validation_log().messages;
    const bool reported = std::any_of(all.begin() + std::ptrdiff_t(before), all.end(), [](const std::string& m) {
        return m.find("SYNC-HAZARD-WRITE-AFTER-WRITE") != std::string::npos;
    });
    EXPECT_TRUE(reported) << all.size() - before << " messages, none a write-after-write hazard";
    all.resize(before);  // the hazard was this test's own
}

}  // namespace
}  // namespace vkfuse::test

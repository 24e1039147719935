#include "vk/engine/fma_probe.hpp"

#include <cstring>
#include <vector>

#include "vk/engine/buffer.hpp"
#include "vk/engine/descriptor_sets.hpp"
#include "vk/engine/recorder.hpp"
#include "vk/engine/timed_commands.hpp"

namespace vkfuse::vk {
namespace {

constexpr std::uint32_t kPairs = 256;  // 4 groups of probe_fma_error's 64

// Operands of the magnitudes the filters meet (pixel values, taps), with
// 24 significant bits each, so that almost every product is inexact.
std::vector<float> probe_pairs() {
    std::vector<float> ab;
    std::uint32_t state = 0x9E3779B9u;
    auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);  // [0, 1), 24 bits
    };
    for (std::uint32_t i = 0; i < kPairs; ++i) {
        const float a = (1.0f + next()) * (i % 2 ? 255.0f : 1.0f);
        const float b = (1.0f + next()) * (i % 3 ? -0.5f : 0.25f);
        ab.push_back(a);
        ab.push_back(b);
    }
    return ab;
}

}  // namespace

bool fma_is_fused(Context::Impl& ctx) {
    const std::vector<float> ab = probe_pairs();
    Buffer pairs(ctx, ab.size() * sizeof(float), MemoryUse::Upload);
    Buffer errors(ctx, kPairs * sizeof(float), MemoryUse::Readback);
    std::memcpy(pairs.mapped(), ab.data(), ab.size() * sizeof(float));
    DescriptorSets sets(ctx);
    const DeviceSpan bound[] = {pairs.span(), errors.span()};
    const VkDescriptorSet set = sets.bind(bound);
    const VkPipeline pipeline = ctx.pipeline("probe_fma_error");
    TimedCommands job(ctx);
    job.record([&](VkCommandBuffer cmd) {
        auto& api = *ctx.api;
        memory_barrier(api, cmd, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_WRITE_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
        api.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        api.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx.layout, 0, 1, &set, 0, nullptr);
        const std::uint32_t count = kPairs;
        api.vkCmdPushConstants(cmd, ctx.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof count, &count);
        api.vkCmdDispatch(cmd, kPairs / 64, 1, 1);
        memory_barrier(api, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    job.run();
    errors.invalidate();
    const auto* got = static_cast<const float*>(errors.mapped());
    for (std::uint32_t i = 0; i < kPairs; ++i) {
        const float a = ab[2 * i], b = ab[2 * i + 1];
        const double exact = double(a) * double(b) - double(a * b);
        if (double(got[i]) != exact) return false;
    }
    return true;
}

}  // namespace vkfuse::vk

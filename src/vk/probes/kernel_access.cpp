#include "vk/probes/kernel_access.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "vk/engine/buffer.hpp"
#include "vk/engine/recorder.hpp"
#include "vk/engine/timed_commands.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

constexpr std::uint32_t kGroup = 256;         // local_size_x of every probe kernel
constexpr std::uint32_t kSharedRounds = 8;    // ROUNDS in probe_shared.comp
constexpr int kFmaRounds = 256;               // ROUNDS in probe_fma.comp
constexpr std::uint32_t kDispatches = 64;     // single-group dispatches timed together

// Push constants of every probe: two device addresses (unused by the
// descriptor-bound kernels) and the element count at byte 16.
struct ProbePush {
    VkDeviceAddress src = 0;
    VkDeviceAddress dst = 0;
    std::uint32_t count = 0;
    std::uint32_t pad = 0;
};

// The layout, the descriptor set (binding 0: source, binding 1: destination)
// and the pipelines of the probe kernels; everything released in any case.
class ProbeKernels {
public:
    ProbeKernels(Context::Impl& ctx, const Buffer& src, const Buffer& dst) : ctx_(ctx), src_(src), dst_(dst) {
        try {
            create_set();
            for (const char* name : {"probe_copy_address", "probe_copy_address_vec4", "probe_copy_bound", "probe_copy_bound_vec4", "probe_shared",
                                     "probe_fma"})
                if (ctx_.device_addresses || std::string_view(name).find("address") == std::string_view::npos)
                    pipelines_[name] = ctx_.create_pipeline(name, layout_);
        } catch (...) {
            release();
            throw;
        }
    }
    ~ProbeKernels() { release(); }
    ProbeKernels(const ProbeKernels&) = delete;
    ProbeKernels& operator=(const ProbeKernels&) = delete;

    // Records `shader` over `count` elements (one per invocation).
    void dispatch(VkCommandBuffer cmd, const std::string& shader, std::uint32_t count) const {
        auto& api = *ctx_.api;
        ProbePush push{src_.address(), dst_.address(), count, 0};
        api.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_.at(shader));
        api.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
        api.vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        const std::uint32_t groups = (count + kGroup - 1) / kGroup;
        if (groups == 0) return;
        const std::uint32_t gx = std::min<std::uint32_t>(groups, 32768);
        api.vkCmdDispatch(cmd, gx, (groups + gx - 1) / gx, 1);
    }

private:
    Context::Impl& ctx_;
    const Buffer& src_;
    const Buffer& dst_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    std::map<std::string, VkPipeline> pipelines_;

    void create_set() {
        auto& api = *ctx_.api;
        VkDescriptorSetLayoutBinding bindings[2]{};
        for (std::uint32_t b = 0; b < 2; ++b) {
            bindings[b].binding = b;
            bindings[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            bindings[b].descriptorCount = 1;
            bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        }
        VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        lci.bindingCount = 2;
        lci.pBindings = bindings;
        check(api.vkCreateDescriptorSetLayout(ctx_.device, &lci, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
        VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pci.maxSets = 1;
        pci.poolSizeCount = 1;
        pci.pPoolSizes = &size;
        check(api.vkCreateDescriptorPool(ctx_.device, &pci, nullptr, &pool_), "vkCreateDescriptorPool");
        VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        ai.descriptorPool = pool_;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &set_layout_;
        check(api.vkAllocateDescriptorSets(ctx_.device, &ai, &set_), "vkAllocateDescriptorSets");
        VkDescriptorBufferInfo infos[2] = {{src_.handle(), 0, VK_WHOLE_SIZE}, {dst_.handle(), 0, VK_WHOLE_SIZE}};
        VkWriteDescriptorSet writes[2]{};
        for (std::uint32_t b = 0; b < 2; ++b) {
            writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            writes[b].dstSet = set_;
            writes[b].dstBinding = b;
            writes[b].descriptorCount = 1;
            writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            writes[b].pBufferInfo = &infos[b];
        }
        api.vkUpdateDescriptorSets(ctx_.device, 2, writes, 0, nullptr);
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ProbePush)};
        VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        plci.setLayoutCount = 1;
        plci.pSetLayouts = &set_layout_;
        plci.pushConstantRangeCount = 1;
        plci.pPushConstantRanges = &range;
        check(api.vkCreatePipelineLayout(ctx_.device, &plci, nullptr, &layout_), "vkCreatePipelineLayout");
    }

    void release() {
        auto& api = *ctx_.api;
        for (auto& [name, pipe] : pipelines_) api.vkDestroyPipeline(ctx_.device, pipe, nullptr);
        pipelines_.clear();
        if (layout_) api.vkDestroyPipelineLayout(ctx_.device, layout_, nullptr);
        if (pool_) api.vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);  // frees set_
        if (set_layout_) api.vkDestroyDescriptorSetLayout(ctx_.device, set_layout_, nullptr);
        layout_ = VK_NULL_HANDLE;
        pool_ = VK_NULL_HANDLE;
        set_layout_ = VK_NULL_HANDLE;
    }
};

constexpr std::uint32_t kNanBits = 0x7FC00000u;  // fills dst before each probe: never within tolerance

// Source values: k / 2048 for k in [0, 999) and, one element in a thousand,
// exactly 1. All are exact in float and stay exact when doubled. probe_fma's
// recurrence converges for the small values and counts its rounds at 1,
// where it gives exactly 0.5 per round: a probe that ran fewer rounds than
// it reports fails its check.
float source_value(std::uint64_t i) {
    const auto k = std::uint32_t((i * 2654435761u) % 1000u);
    return k == 999u ? 1.0f : float(k) / 2048.0f;
}

// What each probe must have written at element i (of floats).
using Expectation = float (*)(std::uint64_t i);
float doubled(std::uint64_t i) { return 2.0f * source_value(i); }
float shared_rotated(std::uint64_t i) {
    const std::uint64_t group = i / kGroup * kGroup, lane = i % kGroup;
    return float(1u << kSharedRounds) * source_value(group + (lane + kSharedRounds) % kGroup);
}
float fma_limit(std::uint64_t i) {
    const double x = source_value(i);
    double y = 0;
    for (int r = 0; r < kFmaRounds; ++r) y = y * x + 0.5;
    return float(y);
}

class Probe {
public:
    Probe(Context::Impl& ctx, std::uint32_t floats, int repeats)
        : ctx_(ctx), floats_(floats), repeats_(repeats), upload_(ctx, bytes(), MemoryUse::Upload),
          src_(ctx, bytes(), MemoryUse::Device), dst_(ctx, bytes(), MemoryUse::Device),
          readback_(ctx, bytes(), MemoryUse::Readback), kernels_(ctx, src_, dst_), job_(ctx) {
        auto* up = static_cast<float*>(upload_.mapped());
        for (std::uint64_t i = 0; i < floats_; ++i) up[i] = source_value(i);
        job_.record([&](VkCommandBuffer cmd) {
            VkBufferCopy region{0, 0, bytes()};
            ctx_.api->vkCmdCopyBuffer(cmd, upload_.handle(), src_.handle(), 1, &region);
            memory_barrier(*ctx_.api, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
        });
        job_.run();
    }

    // Median seconds of `shader` over `count` elements; its output is then
    // checked against `expect` for every float. dst starts as NaN, so a probe
    // that writes nothing cannot pass on what the previous probe left there.
    double time_checked(const std::string& shader, std::uint32_t count, Expectation expect) {
        job_.record([&](VkCommandBuffer cmd) {
            ctx_.api->vkCmdFillBuffer(cmd, dst_.handle(), 0, VK_WHOLE_SIZE, kNanBits);
            memory_barrier(*ctx_.api, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
        });
        job_.run();
        job_.record([&](VkCommandBuffer cmd) { kernels_.dispatch(cmd, shader, count); });
        const double seconds = job_.median_of(repeats_);
        check_output(shader, expect);
        return seconds;
    }

    // Seconds per single-group dispatch, kDispatches of them with barriers.
    double time_dispatch() {
        job_.record([&](VkCommandBuffer cmd) {
            for (std::uint32_t d = 0; d < kDispatches; ++d) {
                if (d > 0)
                    memory_barrier(*ctx_.api, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
                kernels_.dispatch(cmd, "probe_copy_bound", kGroup);
            }
        });
        return job_.median_of(repeats_) / kDispatches;
    }

    bool device_timed() const { return job_.device_timed(); }

private:
    Context::Impl& ctx_;
    std::uint32_t floats_;
    int repeats_;
    Buffer upload_, src_, dst_, readback_;
    ProbeKernels kernels_;
    TimedCommands job_;

    VkDeviceSize bytes() const { return VkDeviceSize(floats_) * sizeof(float); }

    void check_output(const std::string& shader, Expectation expect) {
        job_.record([&](VkCommandBuffer cmd) {
            memory_barrier(*ctx_.api, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
            VkBufferCopy region{0, 0, bytes()};
            ctx_.api->vkCmdCopyBuffer(cmd, dst_.handle(), readback_.handle(), 1, &region);
            memory_barrier(*ctx_.api, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        });
        job_.run();
        readback_.invalidate();
        const auto* out = static_cast<const float*>(readback_.mapped());
        for (std::uint64_t i = 0; i < floats_; ++i) {
            const float want = expect(i);
            if (!(std::fabs(out[i] - want) <= 1e-5f * std::fabs(want)))
                throw Error(ErrorKind::Device, ctx_.info.name + ": device probe " + shader + " wrote " +
                                                   std::to_string(out[i]) + " at element " + std::to_string(i) +
                                                   ", expected " + std::to_string(want));
        }
    }
};

}  // namespace

KernelAccess measure_kernel_access(Context& context, std::uint64_t bytes, int repeats) {
    if (bytes < 4096 || repeats < 1)
        throw Error(ErrorKind::InvalidArgument, "kernel access probe: bytes must be >= 4096 and repeats >= 1");
    // Whole vec4 groups, so every probe covers every float and probe_shared's
    // groups are complete; no more than one descriptor may bind
    // (maxStorageBufferRange: 128 MiB on lavapipe, at most 4 GiB - 1 anywhere).
    const std::uint64_t per_step = std::uint64_t(4) * kGroup;
    const std::uint64_t range = ContextAccess::of(context).properties.limits.maxStorageBufferRange;
    const auto floats = std::uint32_t(std::min(bytes, range) / sizeof(float) / per_step * per_step);
    Probe probe(ContextAccess::of(context), floats, repeats);
    KernelAccess r;
    r.floats = floats;
    const double n = floats;
    r.device_addresses = ContextAccess::of(context).device_addresses;
    if (r.device_addresses) {
        r.address_ns = probe.time_checked("probe_copy_address", floats, doubled) / n * 1e9;
        r.address_vec4_ns = probe.time_checked("probe_copy_address_vec4", floats / 4, doubled) / n * 1e9;
    }
    r.bound_ns = probe.time_checked("probe_copy_bound", floats, doubled) / n * 1e9;
    r.bound_vec4_ns = probe.time_checked("probe_copy_bound_vec4", floats / 4, doubled) / n * 1e9;
    r.shared_exchange_ns = probe.time_checked("probe_shared", floats, shared_rotated) / (n * kSharedRounds) * 1e9;
    r.fma_gflops = 2.0 * kFmaRounds * n / probe.time_checked("probe_fma", floats / 4, fma_limit) * 1e-9;
    r.dispatch_us = probe.time_dispatch() * 1e6;
    r.device_timed = probe.device_timed();
    return r;
}

}  // namespace vkfuse::vk

// vkfuse inside a caller's own Vulkan work, as a perception stack embeds it:
// the caller's instance, device and queue (caller_vulkan.hpp), its buffers
// holding a DIGIT-like pair of 8-bit frames, and its command buffer, into
// which the plan's cycle is appended between the caller's own commands. Then
// the same plan submitted asynchronously, the caller's next submission
// waiting on the plan's timeline semaphore. Runs under the validation layer;
// exit 0 when both fused images agree with the double-precision reference
// (docs/spec.md: 1e-5 outside max-abs near-ties) and the layer stayed
// silent, 1 when not, 2 on error.
//   cmake -S examples/caller_command_buffer -B b -DCMAKE_PREFIX_PATH=P && cmake --build b && b/caller_command_buffer
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include <vkfuse/vkfuse.hpp>

#include "caller_vulkan.hpp"

namespace {

constexpr int kHeight = 240, kWidth = 320, kChannels = 3, kFrames = 2;

// A DIGIT-like pair: one smooth gel under two illuminations, with sensor noise.
std::vector<std::uint8_t> digit_pair(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 2.0f);
    std::vector<std::uint8_t> out(std::size_t(kFrames) * kHeight * kWidth * kChannels);
    for (int k = 0; k < kFrames; ++k)
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                for (int c = 0; c < kChannels; ++c) {
                    const float light = k == 0 ? 150.0f : (c == 1 ? 170.0f : 40.0f);
                    const float shade = 0.6f + 0.4f * std::sin(0.03f * float(x + 2 * k * y)) * std::cos(0.02f * float(y));
                    const float v = light * shade + noise(rng);
                    out[((std::size_t(k) * kHeight + y) * kWidth + x) * kChannels + c] =
                        std::uint8_t(std::clamp(v, 0.0f, 255.0f));
                }
    return out;
}

vkfuse::ImageD reference_of(const std::vector<std::uint8_t>& pair, const vkfuse::FusionSpec& spec) {
    std::vector<vkfuse::ImageD> frames;
    const std::size_t n = std::size_t(kHeight) * kWidth * kChannels;
    for (int k = 0; k < kFrames; ++k) {
        vkfuse::ImageD f(kHeight, kWidth, kChannels);
        for (std::size_t i = 0; i < n; ++i) f.data[i] = pair[std::size_t(k) * n + i] / 255.0;
        frames.push_back(std::move(f));
    }
    return vkfuse::fuse_reference(frames, spec);
}

// Whether the fused floats agree with the reference (a few max-abs near-ties allowed).
bool agrees(const char* what, const float* fused, const vkfuse::ImageD& reference) {
    std::size_t over = 0;
    double worst = 0;
    for (std::size_t i = 0; i < reference.data.size(); ++i) {
        const double d = std::abs(double(fused[i]) - reference.data[i]);
        worst = std::max(worst, d);
        over += d > 1e-5;
    }
    const bool ok = over <= std::max<std::size_t>(4, reference.data.size() / 10000);
    std::printf("%s: max |vulkan - reference| %.3g, %zu samples over 1e-5: %s\n", what, worst, over,
                ok ? "agree" : "DIFFER");
    return ok;
}

}  // namespace

int main() {
    try {
        caller::Device device(/*validation=*/true);
        vkfuse::Context context = vkfuse::make_context(device.describe());
        std::printf("vkfuse %s on the caller's %s\n", std::string(vkfuse::kVersion).c_str(),
                    context.device().name.c_str());

        vkfuse::PlanConfig config;  // wavelet bior4.4, 3 levels, mean / max-abs
        config.height = kHeight;
        config.width = kWidth;
        config.channels = kChannels;
        config.frames = kFrames;
        config.input = vkfuse::PixelType::U8;
        const std::size_t fused_bytes = std::size_t(kHeight) * kWidth * kChannels * sizeof(float);
        caller::HostBuffer frames = device.buffer(std::size_t(kFrames) * kHeight * kWidth * kChannels);
        caller::HostBuffer fused = device.buffer(fused_bytes);   // the plan writes here
        caller::HostBuffer copy = device.buffer(fused_bytes);    // the caller's own work reads it on
        vkfuse::Plan plan = vkfuse::make_plan(context, config, {frames.range(), fused.range()});

        // 1. The cycle inside the caller's command buffer, between its own commands.
        const std::vector<std::uint8_t> first = digit_pair(1);
        std::memcpy(frames.mapped, first.data(), first.size());
        VkCommandBuffer cmd = device.begin();
        vkCmdFillBuffer(cmd, copy.buffer, 0, VK_WHOLE_SIZE, 0);  // the caller's work before
        vkfuse::record(plan, cmd);
        const VkBufferCopy region{0, 0, fused_bytes};
        vkCmdCopyBuffer(cmd, fused.buffer, copy.buffer, 1, &region);  // and after
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                             nullptr, 0, nullptr);
        device.submit_and_wait(cmd);
        vkfuse::finished(plan);
        bool ok = agrees("recorded into the caller's command buffer", static_cast<const float*>(copy.mapped),
                         reference_of(first, config.fusion));
        const vkfuse::Metrics m = plan.metrics(0);
        std::printf("metrics: sharpness %.6g, contrast %.6g\n", m.sharpness, m.contrast);

        // 2. Submitted without waiting; the caller's next submission waits on
        // the plan's timeline semaphore, then copies the fused image on.
        const std::vector<std::uint8_t> second = digit_pair(2);
        std::memcpy(frames.mapped, second.data(), second.size());
        const std::uint64_t done = vkfuse::submit(plan);
        cmd = device.begin();
        vkCmdCopyBuffer(cmd, fused.buffer, copy.buffer, 1, &region);
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                             nullptr, 0, nullptr);
        device.submit_and_wait(cmd, vkfuse::timeline(plan), done);
        vkfuse::wait(plan);
        ok = agrees("submitted, signalling the timeline", static_cast<const float*>(copy.mapped),
                    reference_of(second, config.fusion)) && ok;

        const std::uint64_t messages = device.validation_messages();
        if (device.validating())
            std::printf("validation messages: %llu\n", static_cast<unsigned long long>(messages));
        else
            std::printf("validation: not checked (VK_LAYER_KHRONOS_validation is not installed)\n");
        return ok && messages == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "caller_command_buffer: %s\n", e.what());
        return 2;
    }
}

// Fuses a DIGIT-sized pair of frames with the wavelet method on the best
// Vulkan device (the CPU reference alone where there is none) and checks the
// GPU's image against the double-precision reference: exit 0 when they agree
// to docs/spec.md's 1e-5 outside max-abs near-ties, 1 when not, 2 on error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <vkfuse/vkfuse.hpp>

int main() {
    try {
        constexpr int kHeight = 240, kWidth = 320, kChannels = 3, kFrames = 2;
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> light(0.1f, 0.9f);
        std::vector<vkfuse::Image> frames;
        for (int k = 0; k < kFrames; ++k) {
            vkfuse::Image f(kHeight, kWidth, kChannels);
            for (float& v : f.data) v = light(rng);
            frames.push_back(f);
        }
        vkfuse::FusionSpec spec;  // wavelet, bior4.4, 3 levels, mean / max-abs
        std::vector<vkfuse::ImageD> exact;
        for (const vkfuse::Image& f : frames) exact.push_back(vkfuse::convert<double>(f));
        const vkfuse::ImageD reference = vkfuse::fuse_reference(exact, spec);
        std::printf("vkfuse %s: reference fused %dx%dx%d\n", std::string(vkfuse::kVersion).c_str(), reference.height,
                    reference.width, reference.channels);

        if (vkfuse::list_devices().empty()) {
            std::printf("no Vulkan device: the CPU reference only\n");
            return 0;
        }
        vkfuse::Context context;
        vkfuse::PlanConfig config;
        config.fusion = spec;
        config.height = kHeight;
        config.width = kWidth;
        config.channels = kChannels;
        config.frames = kFrames;
        vkfuse::Plan plan(context, config);
        std::vector<vkfuse::FrameView> views;
        for (const vkfuse::Image& f : frames) views.push_back(vkfuse::FrameView::of(f));
        plan.run(views);
        const vkfuse::Image& fused = plan.fused(0);
        std::size_t over = 0;
        double worst = 0;
        for (std::size_t i = 0; i < fused.data.size(); ++i) {
            const double d = std::abs(double(fused.data[i]) - reference.data[i]);
            worst = std::max(worst, d);
            over += d > 1e-5;
        }
        // max-abs near-ties: a few samples per image may pick the other frame.
        const bool ok = over <= std::max<std::size_t>(4, fused.data.size() / 10000);
        std::printf("%s: max |vulkan - reference| %.3g, %zu samples over 1e-5: %s\n", context.device().name.c_str(),
                    worst, over, ok ? "agree" : "DIFFER");
        return ok ? 0 : 1;
    } catch (const vkfuse::Error& e) {
        std::fprintf(stderr, "fuse_installed: %s\n", e.what());
        return 2;
    }
}

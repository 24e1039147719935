// Precision::Fp16Storage: the _fp16 kernels (float16 planes, float32
// arithmetic) against the double reference. docs/spec.md sets no tolerance for
// reduced precision, so these bounds are what float16 storage gives with
// margin, measured on lavapipe (below); they catch a kernel that stores the
// wrong thing, not a rounding slightly worse than measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

struct Fp16Case {
    FusionSpec spec;
    double max_abs;   // worst sample of the fused image
    double mean_abs;  // mean over samples
};

FusionSpec spec_of(Method m, Wavelet w = Wavelet::Bior44, WaveletMode mode = WaveletMode::Periodization) {
    FusionSpec s;
    s.method = m;
    s.wavelet = w;
    s.mode = mode;
    // max-abs flips wherever two frames' coefficients are within float16's
    // rounding, far more often than in float32: max keeps every sample comparable.
    if (m == Method::Laplacian || m == Method::Wavelet) s.detail_rule = Rule::Max;
    return s;
}

// Measured max / mean abs error on lavapipe, 80 x 112 x 3, K = 3, S = 2 (worst sensor):
//   channel-sum 2.4e-4 / 9e-5, brovey 4.7e-4 / 1.3e-4, laplacian 1.3e-3 / 2.3e-4,
//   wavelets 1.7e-3 (bior2.2 periodization) to 6.0e-3 / 1.0e-3 (bior4.4
//   symmetric: its eight lifting steps per level store every step).
// Metrics: relative error <= 6e-5. Bounds: about twice those.
std::vector<Fp16Case> cases() {
    std::vector<Fp16Case> out{{spec_of(Method::ChannelSum), 5e-4, 2e-4},
                              {spec_of(Method::Brovey), 1e-3, 3e-4},
                              {spec_of(Method::Laplacian), 3e-3, 5e-4}};
    for (Wavelet w : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44})
        for (WaveletMode m : {WaveletMode::Periodization, WaveletMode::Symmetric})
            out.push_back({spec_of(Method::Wavelet, w, m), 1.2e-2, 2e-3});
    return out;
}

PlanConfig config_of(const FusionSpec& spec, Precision p) {
    PlanConfig cfg;
    cfg.fusion = spec;
    cfg.height = 80;
    cfg.width = 112;
    cfg.channels = 3;
    cfg.frames = 3;
    cfg.sensors = 2;
    cfg.precision = p;
    return cfg;
}

std::vector<ImageD> frames_for(std::uint32_t seed) {
    std::vector<ImageD> frames;
    for (int i = 0; i < 6; ++i)
        frames.push_back(i % 2 ? random_image(80, 112, 3, seed + std::uint32_t(i)) : structured_image(80, 112, 3, seed + std::uint32_t(i)));
    return frames;
}

double relative(double got, double want) { return std::abs(got - want) / std::max(std::abs(want), 1e-12); }

class VulkanFp16Storage : public VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        if (!ctx().device().fp16_storage) GTEST_SKIP() << ctx().device().name << " has no 16-bit storage";
    }
};

TEST_F(VulkanFp16Storage, EveryMethodWithinFloat16Rounding) {
    const std::vector<ImageD> frames = frames_for(40);
    std::vector<Image> f32;
    for (const auto& f : frames) f32.push_back(convert<float>(f));
    for (const Fp16Case& c : cases()) {
        SCOPED_TRACE(std::string(to_string(c.spec.method)) + " " + std::string(to_string(c.spec.wavelet)) + "/" +
                     std::string(to_string(c.spec.mode)));
        Plan half = run_plan(ctx(), config_of(c.spec, Precision::Fp16Storage), f32);
        Plan full = run_plan(ctx(), config_of(c.spec, Precision::Fp32), f32);
        for (int s = 0; s < 2; ++s) {
            const ImageD ref = fuse_reference(std::span(frames).subspan(std::size_t(s) * 3, 3), c.spec);
            double worst = 0, sum = 0, from_fp32 = 0;
            for (std::size_t i = 0; i < ref.data.size(); ++i) {
                const double d = std::abs(double(half.fused(s).data[i]) - ref.data[i]);
                worst = std::max(worst, d);
                sum += d;
                from_fp32 = std::max(from_fp32, double(std::abs(half.fused(s).data[i] - full.fused(s).data[i])));
            }
            EXPECT_LE(worst, c.max_abs) << "sensor " << s;
            EXPECT_LE(sum / double(ref.data.size()), c.mean_abs) << "sensor " << s;
            // The fp16 kernels ran: float32 storage alone is 1e3 times closer.
            // Channel-sum and Brovey fuse from the frames as uploaded straight
            // into the image read back, with no plane in between: only their
            // metrics read float16 planes, and they are checked below.
            const bool pointwise = c.spec.method == Method::ChannelSum || c.spec.method == Method::Brovey;
            if (!pointwise) EXPECT_GT(from_fp32, 1e-5) << "sensor " << s;
            else EXPECT_LE(from_fp32, 1e-6) << "sensor " << s;
            const Metrics want = metrics_reference(ref);
            EXPECT_LE(relative(half.metrics(s).sharpness, want.sharpness), 2e-4) << "sensor " << s;
            EXPECT_LE(relative(half.metrics(s).contrast, want.contrast), 2e-4) << "sensor " << s;
        }
    }
}

// A float16 plane overflows past 65504: the results say so instead of
// handing back Inf or NaN.
TEST_F(VulkanFp16Storage, OverflowIsAnErrorNotInf) {
    std::vector<Image> f32;
    for (const auto& f : frames_for(50)) {
        Image big = convert<float>(f);
        for (float& v : big.data) v *= 1e6f;
        f32.push_back(big);
    }
    Plan plan = run_plan(ctx(), config_of(spec_of(Method::Wavelet), Precision::Fp16Storage), f32);
    expect_error([&] { (void)plan.fused(0); }, "sensor 0", ErrorKind::Numeric, "float16's range");
    expect_error([&] { (void)plan.metrics(1); }, "sensor 1", ErrorKind::Numeric, "float16's range");
    // The same frames in float32 are fine.
    Plan full = run_plan(ctx(), config_of(spec_of(Method::Wavelet), Precision::Fp32), f32);
    EXPECT_TRUE(std::isfinite(full.fused(0).data[0]));
}

}  // namespace
}  // namespace vkfuse::test

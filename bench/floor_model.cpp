#include "floor_model.hpp"

#include "core/wavelet.hpp"

namespace vkfuse::bench {
namespace {

// Every pass reads what it needs once and writes its result once; stages that
// can share a pass do (the quad kernels' access pattern taken to its end).
// With N = H W C samples per frame, K frames, S sensors, n_l = N / 4^l:
//
//   pointwise   frames -> fuse -> fused planes + read-back image       in + 2 S N
//               planes -> metrics (gradient, luma moments, |I - B|)    2 S N
//   laplacian   level 0: frames -> pyrDown + fuse G0 - pyrUp(G1)      in + S K n_1 + S n_0
//               level l: G_l -> G_{l+1}, fused level l                 S K (n_l + n_{l+1}) + S n_l
//               top: G_L -> base rule                                  S K n_L + S n_L
//               collapse l = L-1 .. 0: R_{l+1}, C_l -> R_l             S (n_{l+1} + 2 n_l)
//               metrics over R_0, writing the read-back image          3 S n_0 (planes, bg, image)
//   wavelet     level l rows: A_l of every frame -> row coefficients   (in or S K n_l) + S K n_l
//               level l columns + fusion: -> fused block, A_{l+1}      S K n_l + S n_l + S K n_{l+1}
//               inverse level l: columns, then rows                    4 S n_l
//               metrics as above                                       3 S n_0
//
// Arithmetic: a filter tap is one multiply-add (pyrDown 10 per output, pyrUp
// 6, a wavelet output F taps), the rules and metrics a few flops per sample.
// The compensated dot products vkfuse's wavelet kernels use for its
// feedback-drift bound are not counted: the floor is what any pipeline of
// the method needs.
constexpr double kMetricFlops = 30;  // per fused pixel: luma, gradient, magnitude, sums, moments
constexpr double kRuleFlops = 2;     // per coefficient and frame

}  // namespace

PipelineCost ideal_pipeline(const Cell& c, bool eight_bit_input) {
    const double N = c.size.pixels() * 3, S = c.sensors, K = c.frames;
    const double in = S * K * N * (eight_bit_input ? 0.25 : 1.0);
    const double metrics = 3 * S * N;  // fused planes and background read, read-back image written
    PipelineCost p;
    p.flops = S * c.size.pixels() * kMetricFlops;
    const int L = c.levels;
    switch (c.method.method) {
        case Method::Laplacian: {
            double n = N;
            p.accesses = in + S * K * N / 4 + S * N;
            p.flops += 2 * S * K * (10 * N / 4 + 6 * N) + kRuleFlops * S * K * N;
            for (int l = 1; l < L; ++l) {
                n /= 4;
                p.accesses += S * K * (n + n / 4) + S * n;
                p.flops += 2 * S * K * (10 * n / 4 + 6 * n) + kRuleFlops * S * K * n;
            }
            p.accesses += S * K * n / 4 + S * n / 4;  // the top level
            for (int l = L - 1; l >= 0; --l) {
                const double nl = N / double(1 << (2 * l));
                p.accesses += S * (nl / 4 + 2 * nl);
                p.flops += 2 * S * 6 * nl;
            }
            p.accesses += metrics;
            p.dispatches = 2 * L + 2;
            break;
        }
        case Method::Wavelet: {
            const double F = core::filter_bank(c.method.wavelet).length;
            for (int l = 0; l < L; ++l) {
                const double n = N / double(1 << (2 * l));
                p.accesses += (l == 0 ? in : S * K * n) + S * K * n;    // rows
                p.accesses += S * K * n + S * n + (l + 1 < L ? S * K * n / 4 : 0);  // columns + fusion
                p.accesses += 4 * S * n;                                // inverse
                p.flops += 2 * F * (2 * S * K * n) + kRuleFlops * S * K * n + 2 * F * (2 * S * n);
            }
            p.accesses += metrics;
            p.dispatches = 4 * L + 1;
            break;
        }
        default:  // channel-sum, brovey, mean
            p.accesses = in + 2 * S * N + metrics - S * N;  // metrics: planes and background read
            p.flops += 4 * S * K * N;
            p.dispatches = 2;
            break;
    }
    return p;
}

double floor_ms(const PipelineCost& p, const vk::KernelAccess& device) {
    const double access_ns = device.bound_vec4_ns / 2;
    const double flop_ns = device.fma_gflops > 0 ? 1.0 / device.fma_gflops : 0;
    return (p.accesses * access_ns + p.flops * flop_ns) * 1e-6 + p.dispatches * device.dispatch_us * 1e-3;
}

}  // namespace vkfuse::bench

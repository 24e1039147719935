// The fusion methods' Vulkan rows (vk/plan/method_recorders.hpp).
#include "vk/plan/method_recorders.hpp"

#include "vk/engine/kernel_codes.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

VkDeviceAddress pointwise(GraphBuilder& g, FrameSource& input, std::optional<DeviceSpan> image, std::uint32_t kernel) {
    return record_pointwise(g, input.frames(), image, kernel, to_string(g.cfg.fusion.method).data());
}
VkDeviceAddress laplacian(GraphBuilder& g, FrameSource& input, std::optional<DeviceSpan>, std::uint32_t) {
    return record_laplacian(g, input);
}
VkDeviceAddress wavelet(GraphBuilder& g, FrameSource& input, std::optional<DeviceSpan>, std::uint32_t) {
    return record_wavelet(g, input);
}

constexpr MethodRecorder kChannelSum{Method::ChannelSum,
                                     GraphShape::Pointwise,
                                     pointwise,
                                     VKFUSE_POINTWISE_CHANNEL_SUM,
                                     0,
                                     0,
                                     1.0 / 3,
                                     0,
                                     nullptr,
                                     nullptr,
                                     FloorChain::Pointwise};
// Brovey: clamp, sum, weight and weighted sum per frame sample.
constexpr MethodRecorder kBrovey{Method::Brovey, GraphShape::Pointwise, pointwise, VKFUSE_POINTWISE_BROVEY, 0, 0, 1, 4,
                                 nullptr, nullptr, FloorChain::Pointwise};
constexpr MethodRecorder kLaplacian{Method::Laplacian, GraphShape::Multiscale, laplacian, 0, 0.4, 0.4, 1, 0,
                                    record_laplacian_decompose, record_laplacian_cached, FloorChain::Pyramid};
constexpr MethodRecorder kWavelet{Method::Wavelet, GraphShape::Multiscale, wavelet, 0, 2.4, 2.4, 1, 0,
                                  record_wavelet_decompose, record_wavelet_cached, FloorChain::Dwt};

}  // namespace

const MethodRecorder& method_recorder(Method m) {
    // No default: a Method without its row here fails to compile (-Wswitch).
    switch (m) {
        case Method::ChannelSum: return kChannelSum;
        case Method::Brovey: return kBrovey;
        case Method::Laplacian: return kLaplacian;
        case Method::Wavelet: return kWavelet;
    }
    throw Error(ErrorKind::InvalidArgument, "--method: invalid method enumerator");
}

}  // namespace vkfuse::vk

// vk/plan/method_recorders.hpp - one row per fusion method on the Vulkan side: how
// a plan records it, and what it costs, for the plan, the memory estimates of
// the CLI and the bench, and the bench's floor model.
//
// method_recorder() switches over every Method with no default, so under
// -Wall -Werror a Method without its row here does not compile (its
// core/method_table.hpp row is checked the same way).
#pragma once
#include <optional>

#include "vk/passes/graph.hpp"

namespace vkfuse::vk {

enum class GraphShape {
    // One kernel from the frames as uploaded to the fused planes, which also
    // writes the read-back image: no unpack, no pack.
    Pointwise,
    // A chain of passes over planes (FrameSource); the metric pass or pack
    // writes the read-back image.
    Multiscale,
};

// The ideal pipeline the bench's floor model prices for a method.
enum class FloorChain {
    Pointwise,  // one pass from the frames to the image
    Pyramid,    // Gaussian and Laplacian pyramids, fused and collapsed
    Dwt,        // a 2-D wavelet transform, fused and inverted
};

struct MethodRecorder {
    Method method;
    GraphShape shape;
    // Records the method's passes for every sensor and returns the address of
    // the fused planes (S*C planes, plane s*C + c). A Pointwise method also
    // writes `image` (the read-back HWC images) when given one.
    VkDeviceAddress (*record)(GraphBuilder& g, FrameSource& input, std::optional<DeviceSpan> image,
                              std::uint32_t pointwise_kernel);
    // Pointwise: the method shaders/pointwise_fuse.comp is specialized for.
    std::uint32_t pointwise_kernel;
    // Device floats the method keeps beyond the upload, the unpacked input and
    // the fused planes, per input float (S*K*C*H*W) and per output float
    // (S*C*H*W): a wavelet every level's coefficient blocks of every frame, a
    // scratch plane set and every level's fused blocks; a Laplacian a Gaussian
    // pyramid (a third more) and its fused levels.
    double floats_per_input, floats_per_output;
    // The ideal pointwise pass (bench floor model): the fraction of each frame
    // it reads and the arithmetic per frame sample it does.
    double read_fraction, flops_per_frame_sample;
    // Fusing many combinations from coefficients decomposed once (the
    // study's cache, study/cached_fusion.hpp): the decomposition of every frame
    // of the input, and the fusion of a batch of combinations from it
    // (graph.hpp's record_*_decompose and record_*_cached). Null for a
    // method that has nothing to decompose: the cache refuses it by name.
    std::vector<PlaneView> (*decompose)(GraphBuilder& g, FrameSource& input);
    VkDeviceAddress (*fuse_cached)(GraphBuilder& g, std::span<const CachedSources> groups, std::uint32_t sources,
                                   DeviceSpan table);
    // The passes the bench's floor model prices as the method's ideal
    // pipeline (bench/floor_model.cpp).
    FloorChain floor_chain;
    bool caches_coefficients() const { return decompose != nullptr; }
};

const MethodRecorder& method_recorder(Method m);

}  // namespace vkfuse::vk

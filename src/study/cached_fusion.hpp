// study/cached_fusion.hpp - one multi-scale fusion (wavelet or Laplacian)
// scored over many combinations of the same frames, each frame decomposed once.
//
// A study fuses every combination of a dataset's settings, for each object
// and for the background. A plan would decompose a frame again in every
// combination it takes part in; here each frame is decomposed once, into a
// coefficient cache on the device, and a cycle fuses a batch of combinations
// straight from it:
//
//   construction, a submit     the group's frames --dwt rows, columns
//   per group of sources:      (Laplacian: unpack, pyrDown chain)--> cache[group][level]
//   score(), per batch:        table (combination b, source s -> k frames of s's group)
//                                cache[group] --rule_fuse (lap_fuse) by table,
//                                               a dispatch per group--> fused levels
//                                --idwt (collapse)--> fused planes (b*S + s)
//                                --metrics, background = source 0's--> partials
//
// The sources are decomposed in groups, each group's levels in buffers one
// descriptor binds whole, so that a cycle reaches the cache through bindings
// rather than device addresses even when the whole cache is larger than
// maxStorageBufferRange (a QVGA study of 23 settings and 9 objects is).
//
// Source 0 is the background: every other source's background_diff is taken
// against source 0's fusion of the same combination, as a plan whose
// background is that fused image would take it.
#pragma once
#include <cstdint>
#include <list>
#include <memory>
#include <span>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::vk {

struct CachedFusionShape {
    FusionSpec fusion;     // the wavelet or the Laplacian method
    int height = 0, width = 0, channels = 3;
    int sources = 0;       // source 0 the background
    int frames = 0;        // per source: the settings
    // The most bytes one group's buffers may hold; 0: the device's
    // maxStorageBufferRange. Less forces smaller groups (tests).
    std::uint64_t max_binding_bytes = 0;
};

class CachedFusion {
public:
    // images: sources x frames, source-major, each height x width x channels,
    // 8-bit or float32 in [0, 1] scale (as a plan takes them).
    CachedFusion(Context& context, const CachedFusionShape& shape, std::span<const FrameView> images);
    ~CachedFusion();
    CachedFusion(const CachedFusion&) = delete;
    CachedFusion& operator=(const CachedFusion&) = delete;

    // Bytes of device memory the decomposition of `shape` takes at its peak
    // (the cache it keeps takes less).
    static std::uint64_t cache_bytes(const CachedFusionShape& shape);
    // Whether the method's Vulkan row decomposes into coefficients a cache
    // can hold (vk/plan/method_recorders.hpp); the constructor refuses the others.
    static bool supports(Method method);

    // Each combination (2 or more distinct frame indices, in fusion order,
    // all combinations of one size): the metrics of sources 1.. fused over
    // those frames, result[b][s - 1].
    std::vector<std::vector<Metrics>> score(std::span<const std::vector<std::size_t>> combinations);
    // Combinations fused per submit: score() takes any number, but a
    // multiple of this fuses none twice.
    std::size_t batch() const;

    struct Graph;

private:
    Context::Impl& ctx_;
    CachedFusionShape shape_;
    struct Cache;
    std::unique_ptr<Cache> cache_;
    std::list<Graph> graphs_;  // per combination size, most recently used last
    bool addressed_ = false;

    Graph& graph_for(std::size_t k);
};

}  // namespace vkfuse::vk

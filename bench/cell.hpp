// One cell of the benchmark matrix: what is run, on what, at what size.
#pragma once
#include <string>

#include "axes.hpp"
#include "vkfuse/fusion.hpp"

namespace vkfuse::bench {

struct Cell {
    MethodVariant method;
    int levels = 0;  // pyramid levels; 0 for the pointwise methods
    Backend backend = Backend::Vulkan;
    Precision precision = Precision::Fp32;
    Size size;
    int frames = 3;   // K
    int sensors = 1;  // S
    std::string skip;  // non-empty: why this cell is not measured

    FusionSpec fusion() const;
    // Cells that differ only in backend share inputs, reference and peer.
    bool same_workload(const Cell& other) const;
    // What the numbers are held in: "fp64" (the CPU reference), "fp32", "fp16".
    std::string precision_name() const;
    // "wavelet/bior4.4 L3 QVGA K3 S1 vulkan", "... vulkan fp16"
    std::string describe() const;
};

}  // namespace vkfuse::bench

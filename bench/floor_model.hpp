// The device's floor under a cell: what the ideal pipeline for the cell's
// method and shape must do (memory accesses, floating-point work, dispatches),
// priced at the costs the probe kernels measured this run
// (vk/probes/kernel_access.hpp). floor_ms / median_ms says how close a cell runs to
// what the device allows a pipeline of that method.
#pragma once
#include "result.hpp"
#include "vk/probes/kernel_access.hpp"

namespace vkfuse::bench {

struct PipelineCost {
    double accesses = 0;  // floats read or written (8-bit input: a word of 4 samples is one)
    double flops = 0;     // a multiply-add is 2
    int dispatches = 0;
};

// The ideal pipeline of one cycle of `c` (all S sensors; RGB frames, as the
// bench's are), from float32 frames (what the bench uploads) or 8-bit ones,
// scored against a background (as the bench's cells are). Wavelet cells are
// periodization, the bench's mode.
PipelineCost ideal_pipeline(const Cell& c, bool eight_bit_input);

// Its time on the probed device: the fixed cost of a cycle (an empty cycle,
// which holds one small dispatch; 0 where not measured), accesses at half a
// bound vec4 copy's cost per float (a copy is a read and a write), flops at
// the multiply-add rate, and one small dispatch for each further pass.
double floor_ms(const PipelineCost& p, const vk::KernelAccess& device, double cycle_fixed_ms = 0);

}  // namespace vkfuse::bench

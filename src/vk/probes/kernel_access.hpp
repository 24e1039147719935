// What a compute kernel pays on this device to reach memory and to compute,
// measured with small probe kernels: the floor under every vkfuse kernel's run
// time. vkfuse's kernels reach their buffers through descriptor bindings
// (device addresses only in plans beyond maxStorageBufferRange); the figures
// show what each path costs per float and per vec4 on the device, and the
// shared-memory figure what a tiled kernel would pay to exchange halos. On a GPU these are tiny; on a CPU implementation such as
// lavapipe they bound how fast any kernel can be.
#pragma once
#include <cstdint>

#include "vkfuse/vk/context.hpp"

namespace vkfuse::vk {

struct KernelAccess {
    std::uint64_t floats = 0;       // floats each copy kernel copies
    bool device_addresses = true;   // the context has them; else the address figures are 0
    double address_ns = 0;          // per float copied (one load + one store), device addresses
    double address_vec4_ns = 0;     // the same, four floats per load and store
    double bound_ns = 0;            // the same through descriptor-bound storage buffers
    double bound_vec4_ns = 0;       // the same, four floats per load and store
    double shared_exchange_ns = 0;  // per invocation and round: store, barrier, load, barrier
    double fma_gflops = 0;          // float32 multiply-add rate, 2 flops each
    double dispatch_us = 0;         // one single-group dispatch plus a barrier, as a plan records them
    bool device_timed = false;      // timestamp queries (true) or host clock around submit + wait
};

// Runs each probe once to warm up and `repeats` times (median) on buffers of
// `bytes`, checks every probe's output against the host (a wrong result
// throws Error(Device): a broken probe must not report a speed), and returns
// the costs. `bytes` beyond the device's maxStorageBufferRange is capped to
// it. Throws Error(InvalidArgument) for bytes < 4 KiB or repeats < 1.
KernelAccess measure_kernel_access(Context& context, std::uint64_t bytes = std::uint64_t(64) << 20, int repeats = 5);

}  // namespace vkfuse::vk

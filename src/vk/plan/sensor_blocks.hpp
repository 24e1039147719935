// A plan's sensors in blocks whose buffers one descriptor binds whole.
//
// Kernels reach memory more cheaply through descriptor bindings than through
// device addresses (shaders/bindings.glsl), but one binding spans at most the
// device's maxStorageBufferRange: 128 MiB on lavapipe, which a QVGA K=3
// wavelet or Laplacian plan of more than 45 sensors exceeds. Such a plan
// records its pass chain once per block of sensors,
//
//   block 0: sensors 0 .. n-1      [method passes] -> metrics -> (pack)
//   block 1: sensors n .. 2n-1     [method passes] -> metrics -> (pack)
//   ...
//
// each block's dispatches bound to that block's range of every per-sensor
// buffer (frames, backgrounds, read-back image and partials), the
// intermediates made once for a block and used by every block in turn. The
// dispatch count is then the passes times the blocks: independent of the
// sensors up to the range, and over it what keeps every kernel bound. Only
// where not even one sensor's buffers fit in a binding do the kernels reach
// memory through device addresses, in one block.
#pragma once
#include <cstdint>
#include <span>

#include "vk/passes/graph.hpp"

namespace vkfuse::vk {

// At most the bytes of the largest buffer a plan of this kind and config
// makes, a multi-scale method's plane sets or a pointwise one's frames and
// image (proportional to its sensors).
double plan_buffer_bytes(const PlanConfig& cfg, PlanKind kind);

// Sensors per block for a plan of `sensors` whose largest buffer takes
// bytes_per_sensor per sensor and whose per-sensor buffers advance by
// `strides` bytes per sensor: every sensor when it all fits one binding
// (range_bytes), else the most that fit whose block offsets in every such
// buffer are multiples of offset_alignment; 0 where no block fits.
std::uint32_t sensors_per_binding(std::uint32_t sensors, double bytes_per_sensor,
                                  std::span<const std::uint64_t> strides, std::uint64_t range_bytes,
                                  std::uint64_t offset_alignment);

}  // namespace vkfuse::vk

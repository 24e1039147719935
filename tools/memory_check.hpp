// memory_check.hpp - what a command will need, from its inputs' headers, and
// a refusal naming the inputs when that is more than the process can take.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "shared_options.hpp"
#include "io/image_header.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse::cli {

// Peak bytes of `vkfuse fuse` with K inputs of this header's shape: an upper
// bound fitted to measured peaks (RSS, 2048 x 2048 x 3, K = 2, 3, 5, both
// backends) with a margin. In units of F, one input as float32:
// - cpu: K x (F decoded + 2F as double + the method's per-frame working set:
//   1.7F for laplacian and wavelet, else 0) + 4F (the result in double and
//   float, the file's bytes) + 2F more for laplacian and wavelet;
// - vulkan: K x (F decoded + F upload + F planes + per-frame intermediates:
//   0.4F laplacian, 1.4F wavelet) + 6F (output planes, read-back, the fused
//   image, the file's bytes) + 0.5F laplacian, 2.5F wavelet. Device buffers
//   count as host memory: they are on lavapipe and integrated GPUs (on a
//   discrete GPU this overestimates);
// - auto: the larger of the two;
// plus the largest decode buffer and the process itself (32 MiB, 192 MiB
// with a Vulkan driver loaded).
// inputs share one shape (checked before).
std::uint64_t fuse_memory_need(const std::vector<io::ImageHeader>& inputs, Method method, Backend backend);

// Peak bytes of `vkfuse metrics`, which decodes every input before scoring:
// all inputs and the background as float; on the cpu the background as double
// (2F) and the largest input as double while it is scored; on vulkan 3.5F per
// distinct input shape for that shape's plan; the largest decode buffer and
// the process as above.
std::uint64_t metrics_memory_need(const std::vector<io::ImageHeader>& inputs, const io::ImageHeader* background,
                                  Backend backend);

// Throws Error(InvalidArgument) "a.png, b.png: fusing needs about 16.0 GiB of
// memory, 11.2 GiB available (MemAvailable)" when need exceeds
// io::available_memory(); doing is "fusing", "scoring" ... Up to 6 paths are
// named, then "and N more".
void require_memory(const std::vector<std::string>& paths, std::string_view doing, std::uint64_t need);

// What a std::bad_alloc becomes when the estimate was too low after all:
// Error(InvalidArgument) "a.png, b.png: out of memory while fusing (about
// 16.0 GiB estimated, 11.2 GiB available (MemAvailable))".
[[noreturn]] void out_of_memory(const std::vector<std::string>& paths, std::string_view doing, std::uint64_t need);

}  // namespace vkfuse::cli

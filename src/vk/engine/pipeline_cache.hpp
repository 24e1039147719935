// vk/engine/pipeline_cache.hpp - the opt-in on-disk pipeline cache
// (ContextOptions::pipeline_cache, VKFUSE_PIPELINE_CACHE): the unrolled
// filter kernels compile once per driver, not at every start, where the
// driver keeps no cache of its own.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "vk/engine/api.hpp"

namespace vkfuse::vk {

// The largest cache file read: a bigger one is ignored (and replaced), so a
// hostile or runaway file never decides how much memory a context takes.
inline constexpr std::uint64_t kMaxPipelineCacheBytes = 64ull << 20;

// Why a cache file's data cannot seed this device's cache ("" where it can):
// its header (VkPipelineCacheHeaderVersionOne) must be whole, of version one,
// and name this device's vendor, device and pipelineCacheUUID. The driver
// checks the rest of the data itself.
std::string pipeline_cache_mismatch(const std::vector<std::uint8_t>& data, const VkPhysicalDeviceProperties& device);

// A VkPipelineCache seeded from `path` where the file exists and suits the
// device, and written back to it (whole or not at all) on destruction when
// pipelines were added. Throws Error(Io) naming the path when its directory
// does not exist, or the path is not a regular file.
class PipelineCache {
public:
    PipelineCache(const Api& api, VkDevice device, const VkPhysicalDeviceProperties& properties, std::string path);
    ~PipelineCache();
    PipelineCache(const PipelineCache&) = delete;
    PipelineCache& operator=(const PipelineCache&) = delete;

    VkPipelineCache handle() const { return cache_; }
    // "PATH: loaded N bytes", or "PATH: starts empty (why)".
    const std::string& state() const { return state_; }
    // Writes the cache to its file now when it holds more than was loaded;
    // throws Error(Io) naming the path where it cannot.
    void save();

private:
    const Api& api_;
    VkDevice device_;
    std::string path_, state_;
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    std::size_t loaded_bytes_ = 0;
};

}  // namespace vkfuse::vk

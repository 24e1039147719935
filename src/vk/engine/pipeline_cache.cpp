#include "vk/engine/pipeline_cache.hpp"

#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/atomic_write.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

std::string pipeline_cache_mismatch(const std::vector<std::uint8_t>& data, const VkPhysicalDeviceProperties& device) {
    VkPipelineCacheHeaderVersionOne header{};
    if (data.size() < sizeof header) return "shorter than a cache header";
    std::memcpy(&header, data.data(), sizeof header);
    if (header.headerSize < sizeof header || header.headerSize > data.size()) return "a header of impossible size";
    if (header.headerVersion != VK_PIPELINE_CACHE_HEADER_VERSION_ONE) return "a header of another version";
    if (header.vendorID != device.vendorID || header.deviceID != device.deviceID ||
        std::memcmp(header.pipelineCacheUUID, device.pipelineCacheUUID, VK_UUID_SIZE) != 0)
        return "made by another device or driver";
    return "";
}

namespace {

// The file's bytes, or why they are not used; nothing read beyond the limit.
std::vector<std::uint8_t> read_cache_file(const std::string& path, std::string& why) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) {
        why = "no file yet";
        return {};
    }
    if (size > kMaxPipelineCacheBytes) {
        why = "larger than " + std::to_string(kMaxPipelineCacheBytes >> 20) + " MiB";
        return {};
    }
    std::vector<std::uint8_t> data(size);
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(data.data()), std::streamsize(size))) {
        why = "unreadable";
        return {};
    }
    return data;
}

}  // namespace

PipelineCache::PipelineCache(const Api& api, VkDevice device, const VkPhysicalDeviceProperties& properties,
                             std::string path)
    : api_(api), device_(device), path_(std::move(path)) {
    const std::filesystem::path p = std::filesystem::absolute(path_);
    if (!std::filesystem::is_directory(p.parent_path()))
        throw Error(ErrorKind::Io, "pipeline cache " + path_ + ": directory " + p.parent_path().string() +
                                       " does not exist");
    struct stat st{};
    if (::lstat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        throw Error(ErrorKind::Io, "pipeline cache " + path_ + ": not a regular file");
    std::string why;
    std::vector<std::uint8_t> data = read_cache_file(path_, why);
    if (why.empty()) why = pipeline_cache_mismatch(data, properties);
    if (!why.empty()) data.clear();
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    info.initialDataSize = data.size();
    info.pInitialData = data.empty() ? nullptr : data.data();
    check(api_.vkCreatePipelineCache(device_, &info, nullptr, &cache_), "vkCreatePipelineCache");
    loaded_bytes_ = data.size();
    state_ = path_ + (why.empty() ? ": loaded " + std::to_string(data.size()) + " bytes" : ": starts empty (" + why + ")");
}

void PipelineCache::save() {
    std::size_t size = 0;
    check(api_.vkGetPipelineCacheData(device_, cache_, &size, nullptr), "vkGetPipelineCacheData");
    if (size <= loaded_bytes_ || size > kMaxPipelineCacheBytes) return;
    std::vector<std::uint8_t> data(size);
    // VK_INCOMPLETE where the cache grew since the size was asked: what fits is a valid cache.
    const VkResult r = api_.vkGetPipelineCacheData(device_, cache_, &size, data.data());
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) check(r, "vkGetPipelineCacheData");
    data.resize(size);
    io::write_atomically(path_, [&](std::FILE* f) { io::write_all(f, data.data(), data.size(), path_); });
    loaded_bytes_ = size;
}

PipelineCache::~PipelineCache() {
    // Best effort: a cache not written costs the next start its compile
    // time, never a result; save() is where a caller learns of a failure.
    try {
        save();
    } catch (const Error&) {
    }
    api_.vkDestroyPipelineCache(device_, cache_, nullptr);
}

}  // namespace vkfuse::vk

// The opt-in pipeline cache (ContextOptions::pipeline_cache): written when a
// context ends, read by the next where its header names this device and
// driver, ignored where it does not (or is too big), and never a reason for
// a different result.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "temp_dir.hpp"
#include "test_support.hpp"
#include "vk/engine/pipeline_cache.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::test {
namespace {

std::vector<std::uint8_t> cache_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A wavelet plan's fused image: the unrolled filter kernels the cache is for.
Image fuse_with(const ContextOptions& options) {
    Context context(options);
    PlanConfig cfg;
    cfg.fusion.method = Method::Wavelet;
    cfg.fusion.levels = 1;  // what 32x48 carries of bior4.4
    cfg.height = 32;
    cfg.width = 48;
    cfg.frames = 2;
    cfg.metrics = {};
    std::vector<Image> frames;
    for (std::uint32_t k = 0; k < 2; ++k) frames.push_back(convert<float>(structured_image(32, 48, 3, 40 + k)));
    Plan plan = run_plan(context, cfg, frames);
    return plan.fused(0);
}

TEST_F(VulkanTest, APipelineCacheIsWrittenThenReadByTheNextContext) {
    TempDir tmp;
    ContextOptions o = validated_options();
    o.pipeline_cache = tmp.file("kernels.cache");
    const Image first = fuse_with(o);
    const std::vector<std::uint8_t> written = cache_bytes(o.pipeline_cache);
    VkPipelineCacheHeaderVersionOne header{};
    ASSERT_GE(written.size(), sizeof header);
    {
        Context context(o);
        EXPECT_EQ(context.pipeline_cache(), o.pipeline_cache + ": loaded " + std::to_string(written.size()) + " bytes");
    }
    const Image again = fuse_with(o);
    ASSERT_EQ(first.data.size(), again.data.size());
    EXPECT_EQ(std::memcmp(first.data.data(), again.data.data(), first.data.size() * 4), 0);
}

TEST_F(VulkanTest, APipelineCacheOfAnotherDeviceOrTooBigIsIgnoredAndReplaced) {
    TempDir tmp;
    ContextOptions o = validated_options();
    o.pipeline_cache = tmp.file("kernels.cache");
    fuse_with(o);
    std::vector<std::uint8_t> bytes = cache_bytes(o.pipeline_cache);
    bytes[16] ^= 0xff;  // the first byte of pipelineCacheUUID
    {
        std::ofstream(o.pipeline_cache, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                                std::streamsize(bytes.size()));
        Context context(o);
        EXPECT_EQ(context.pipeline_cache(), o.pipeline_cache + ": starts empty (made by another device or driver)");
    }
    {
        std::ofstream(o.pipeline_cache, std::ios::binary).write("VKFUSE", 6);
        Context context(o);
        EXPECT_EQ(context.pipeline_cache(), o.pipeline_cache + ": starts empty (shorter than a cache header)");
    }
    std::filesystem::resize_file(o.pipeline_cache, vk::kMaxPipelineCacheBytes + 1);  // sparse: never read
    {
        Context context(o);
        EXPECT_EQ(context.pipeline_cache(), o.pipeline_cache + ": starts empty (larger than 64 MiB)");
    }
    fuse_with(o);  // replaced whole by a cache of this device
    Context context(o);
    EXPECT_NE(context.pipeline_cache().find(": loaded "), std::string::npos) << context.pipeline_cache();
}

TEST_F(VulkanTest, APipelineCacheWhereNoFileCanBeIsRefused) {
    TempDir tmp;
    ContextOptions o = validated_options();
    o.pipeline_cache = tmp.file("no-such-dir/kernels.cache");
    try {
        Context context(o);
        ADD_FAILURE() << "a cache in a missing directory was taken";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Io);
        EXPECT_NE(std::string(e.what()).find("no-such-dir does not exist"), std::string::npos) << e.what();
    }
    o.pipeline_cache = tmp.file("");
    EXPECT_THROW(Context{o}, Error);  // a directory is no cache file
}

}  // namespace
}  // namespace vkfuse::test

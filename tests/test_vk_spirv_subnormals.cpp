// vk::preserving_subnormals: every embedded kernel, patched as a GPU that
// offers shaderDenormPreserveFloat32 builds it, is still a valid module
// (spirv-val, where spirv-tools is installed) and asks for DenormPreserve 32
// on its entry point, once. lavapipe never takes the patch (it keeps
// subnormals without being asked and does not offer the mode), so this is
// where it is checked on every host.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "temp_dir.hpp"
#include "vk/engine/shader_registry.hpp"
#include "vk/engine/spirv_subnormals.hpp"

namespace vkfuse::test {
namespace {

struct Found {
    int capabilities = 0, modes = 0, entry_points = 0;
};

// Counts DenormPreserve capabilities, DenormPreserve 32 execution modes and
// entry points, walking the module as a reader would.
Found walk(const std::vector<std::uint32_t>& m) {
    Found f;
    for (std::size_t at = 5; at < m.size();) {
        const std::uint32_t op = m[at] & 0xffffu, words = m[at] >> 16;
        EXPECT_GT(words, 0u);
        if (words == 0) break;
        if (op == 17 && m[at + 1] == 4464) ++f.capabilities;
        if (op == 16 && words == 4 && m[at + 2] == 4459 && m[at + 3] == 32) ++f.modes;
        if (op == 15) ++f.entry_points;
        at += words;
    }
    return f;
}

TEST(SpirvSubnormals, EveryKernelPatchedAsksOnceAndStaysValid) {
    TempDir dir;
    // Found at configure time; a test program carried to another machine may
    // not find it there.
    const std::string val = std::filesystem::exists(VKFUSE_SPIRV_VAL) ? VKFUSE_SPIRV_VAL : "";
    if (val.empty()) std::printf("spirv-val is not installed: patched modules are checked by structure only\n");
    int checked = 0;
    for (const std::string& name : vk::shader_names()) {
        SCOPED_TRACE(name);
        const auto embedded = vk::shader_spirv(name);
        const std::vector<std::uint32_t> patched = vk::preserving_subnormals(embedded);
        const Found f = walk(patched);
        EXPECT_EQ(f.entry_points, 1);
        EXPECT_EQ(f.capabilities, 1);
        EXPECT_EQ(f.modes, f.entry_points);
        EXPECT_GT(patched.size(), embedded.size());
        EXPECT_EQ(vk::preserving_subnormals(patched), patched) << "patched twice";
        if (!val.empty()) {
            const std::string file = dir.file(name + ".spv");
            std::ofstream(file, std::ios::binary)
                .write(reinterpret_cast<const char*>(patched.data()), std::streamsize(patched.size() * 4));
            const std::string command = val + " --target-env vulkan1.2 " + file + " 2>&1";
            EXPECT_EQ(std::system(command.c_str()), 0) << command;
        }
        ++checked;
    }
    EXPECT_GT(checked, 10);
}

TEST(SpirvSubnormals, WordsThatAreNotAModuleAreAnError) {
    const std::vector<std::uint32_t> empty, not_spirv{1, 2, 3, 4, 5, 6};
    const auto patch = [](const std::vector<std::uint32_t>& words) { return [&words] { vk::preserving_subnormals(words); }; };
    expect_error(patch(empty), "SPIR-V module", ErrorKind::Device, "no SPIR-V header");
    expect_error(patch(not_spirv), "SPIR-V module", ErrorKind::Device, "no SPIR-V header");
    const auto kernel = vk::shader_spirv(vk::shader_names().front());
    std::vector<std::uint32_t> cut(kernel.begin(), kernel.begin() + 6);  // the header and one word
    cut[5] = (10u << 16) | 17u;  // an OpCapability of ten words
    expect_error(patch(cut), "SPIR-V module", ErrorKind::Device, "runs past the module's end");
}

}  // namespace
}  // namespace vkfuse::test

// The push-constant contract, field by field: every dispatch names each
// scalar it pushes as the kernel's GLSL Push block does, and the recorder
// checks name, type and offset against the kernel's SPIR-V
// (vk/engine/push_constants.hpp, vk/engine/kernel_interface.hpp). Here a copy of a
// kernel's SPIR-V has two fields of its block swapped, as an edit of the
// GLSL that forgot the C++ side would leave it, and the plan that dispatches
// it is refused at build, naming the kernel and the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "test_support.hpp"
#include "vk/engine/context_impl.hpp"
#include "vk/engine/kernel_codes.hpp"
#include "vk/engine/kernel_interface.hpp"
#include "vk/engine/shader_registry.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

// A literal string as SPIR-V packs it (nul-terminated, padded, low byte first).
std::vector<std::uint32_t> packed(const std::string& s) {
    std::vector<std::uint32_t> words((s.size() + 4) / 4, 0u);
    for (std::size_t i = 0; i < s.size(); ++i) words[i / 4] |= std::uint32_t(static_cast<unsigned char>(s[i])) << (8 * (i % 4));
    return words;
}

// The kernel with the names of two push-block members swapped: the block now
// declares b where a was and a where b was (both of the same type).
std::vector<std::uint32_t> with_swapped_members(std::span<const std::uint32_t> spirv, const std::string& a,
                                                const std::string& b) {
    std::vector<std::uint32_t> out(spirv.begin(), spirv.end());
    const std::vector<std::uint32_t> wa = packed(a), wb = packed(b);
    EXPECT_EQ(wa.size(), wb.size()) << "the swap keeps the instruction lengths";
    int swapped = 0;
    for (std::size_t at = 5; at < out.size();) {
        const std::uint32_t op = out[at] & 0xffffu, count = out[at] >> 16;
        if (op == 6 && count == 3 + wa.size()) {  // OpMemberName struct member "name"
            auto name = out.begin() + std::ptrdiff_t(at + 3);
            if (std::equal(wa.begin(), wa.end(), name)) {
                std::copy(wb.begin(), wb.end(), name);
                ++swapped;
            } else if (std::equal(wb.begin(), wb.end(), name)) {
                std::copy(wa.begin(), wa.end(), name);
                ++swapped;
            }
        }
        at += count;
    }
    EXPECT_EQ(swapped, 2);
    return out;
}

FusionSpec spec_of(Method m) {
    FusionSpec s;
    s.method = m;
    return s;
}

class PushContract : public VulkanTest {};

TEST_F(PushContract, EveryDispatchOfEveryMethodNamesItsFields) {
    // Building and running a plan of each method checks each of its
    // dispatches (a failure throws at build); this pins that it does.
    for (Method m : {Method::ChannelSum, Method::Brovey, Method::Laplacian, Method::Wavelet}) {
        PlanConfig cfg;
        cfg.fusion = spec_of(m);
        cfg.height = 96;
        cfg.width = 128;
        cfg.frames = 3;
        try {
            Plan plan(ctx(), cfg);
        } catch (const Error& e) {
            ADD_FAILURE() << to_string(m) << ": " << e.what();
        }
    }
}

TEST_F(PushContract, AKernelWhosePushFieldsMovedIsRefusedNamingTheField) {
    ContextOptions bound = validated_options();
    bound.kernel_buffers = KernelBuffers::Bound;  // the bound variant's block, whose scalars start at byte 0
    Context context(bound);
    Context::Impl& impl = vk::ContextAccess::of(context);
    // pointwise_fuse.comp's block: pixels, channels, is_u8, scaled_threshold, quads, ...
    impl.use_kernel_interface("pointwise_fuse",
                              vk::reflect_kernel(with_swapped_members(vk::shader_spirv("pointwise_fuse"), "is_u8", "quads")));
    PlanConfig cfg;
    cfg.fusion = spec_of(Method::Brovey);
    cfg.height = 24;
    cfg.width = 32;
    cfg.frames = 3;
    try {
        Plan plan(context, cfg);
        ADD_FAILURE() << "a plan dispatching pointwise_fuse with its fields swapped was built";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.kind(), ErrorKind::Device) << what;
        EXPECT_NE(what.find("pointwise_fuse"), std::string::npos) << what;
        EXPECT_NE(what.find("uint quads at byte 8"), std::string::npos) << what;
        EXPECT_NE(what.find("gave uint is_u8 at byte 8"), std::string::npos) << what;
    }
    // The unmodified kernel in another context still builds.
    EXPECT_NO_THROW(Plan(ctx(), cfg));
}

TEST(KernelPushBlock, MembersAreReadWithNameTypeAndOffset) {
    const vk::KernelInterface k = vk::reflect_kernel(vk::shader_spirv("rule_fuse"));
    ASSERT_EQ(k.push.size(), 17u);
    EXPECT_EQ(k.push[0].name, "width");
    EXPECT_EQ(k.push[0].type, vk::PushType::I32);
    EXPECT_EQ(k.push[3].name, "plane_stride");
    EXPECT_EQ(k.push[3].type, vk::PushType::U32);
    EXPECT_EQ(k.push[3].offset, 12u);
    EXPECT_EQ(k.push[16].name, "group_period");
    EXPECT_EQ((k.local_size), (std::array<std::uint32_t, 3>{VKFUSE_LINE_GROUP, 1, 1}));
    EXPECT_EQ((vk::reflect_kernel(vk::shader_spirv("sparse_compose")).local_size),
              (std::array<std::uint32_t, 3>{16, 16, 1}));
    const vk::KernelInterface addressed = vk::reflect_kernel(vk::shader_spirv("rule_fuse_addr"));
    ASSERT_EQ(addressed.push.size(), 5u + 17u);
    EXPECT_EQ(addressed.push[0].type, vk::PushType::Address);
    EXPECT_EQ(addressed.push[5].name, "width");
    EXPECT_EQ(addressed.push[5].offset, 40u);
}

}  // namespace
}  // namespace vkfuse::test

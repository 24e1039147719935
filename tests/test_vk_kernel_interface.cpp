// Every kernel's interface is read from its SPIR-V (vk/engine/kernel_interface.hpp)
// and each dispatch is checked against it. These tests pin the reader to
// kernels whose declarations are known, in both binding variants.
#include <gtest/gtest.h>

#include <string>

#include "vk/engine/context_impl.hpp"
#include "vk/engine/kernel_interface.hpp"
#include "vk/engine/shader_registry.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::test {
namespace {

TEST(KernelInterface, BoundVariantsDeclareTheirBuffersAndScalars) {
    // pack.comp: 4 buffers; pixels, channels, quads.
    const vk::KernelInterface pack = vk::reflect_kernel(vk::shader_spirv("pack"));
    EXPECT_EQ(pack.bindings, 4u);
    EXPECT_EQ(pack.push_bytes, 12u);
    // metrics.comp: 7 buffers; 11 scalars.
    const vk::KernelInterface metrics = vk::reflect_kernel(vk::shader_spirv("metrics_fp16"));
    EXPECT_EQ(metrics.bindings, 7u);
    EXPECT_EQ(metrics.push_bytes, 44u);
}

TEST(KernelInterface, AddressedVariantsCarryTheBuffersAsAddresses) {
    // The same lists as 8-byte addresses before the scalars, no bindings.
    const vk::KernelInterface pack = vk::reflect_kernel(vk::shader_spirv("pack_addr"));
    EXPECT_EQ(pack.bindings, 0u);
    EXPECT_EQ(pack.push_bytes, 4u * 8u + 12u);
    const vk::KernelInterface metrics = vk::reflect_kernel(vk::shader_spirv("metrics_fp16_addr"));
    EXPECT_EQ(metrics.bindings, 0u);
    EXPECT_EQ(metrics.push_bytes, 7u * 8u + 44u);
}

// What the context provides is what the kernels need: no bound variant
// declares more buffers than the shared descriptor set layout holds, and no
// variant more push-constant bytes than its pipeline layout's range (the
// guaranteed 128) - a kernel past either would read unbound memory.
TEST(KernelInterface, EveryKernelFitsTheSharedLayout) {
    for (const std::string& name : vk::shader_names()) {
        const vk::KernelInterface k = vk::reflect_kernel(vk::shader_spirv(name));
        EXPECT_LE(k.bindings, kMaxKernelBuffers) << name;
        EXPECT_LE(k.push_bytes, kPushConstantBytes) << name;
    }
}

TEST(KernelInterface, SharedPushBlocksDeclareTheirBuffersToo) {
    // rule_fuse.comp: 5 buffers, seventeen 4-byte scalars.
    EXPECT_EQ(vk::reflect_kernel(vk::shader_spirv("rule_fuse")).bindings, 5u);
    EXPECT_EQ(vk::reflect_kernel(vk::shader_spirv("rule_fuse")).push_bytes, 17u * 4u);
    EXPECT_EQ(vk::reflect_kernel(vk::shader_spirv("rule_fuse_addr")).push_bytes, 5u * 8u + 17u * 4u);
    // dwt_forward.comp's block comes from line.glsl: src, dst, scheme, regions;
    // thirteen scalars.
    const vk::KernelInterface line = vk::reflect_kernel(vk::shader_spirv("dwt_forward"));
    EXPECT_EQ(line.bindings, 4u);
    EXPECT_EQ(line.push_bytes, 13u * 4u);
    EXPECT_EQ(vk::reflect_kernel(vk::shader_spirv("dwt_forward_fp16_addr")).push_bytes, 4u * 8u + 13u * 4u);
    // The lifting kernels share the block, and bind every buffer of it.
    EXPECT_EQ(vk::reflect_kernel(vk::shader_spirv("lift_forward")).bindings, 4u);
}

// float16 planes are storage only: no module needs shaderFloat16, which the
// context neither requires nor enables (16-bit storage is enough), and the
// compensated kernels (and only they) take the context's SPLIT_PRODUCTS.
TEST(KernelInterface, Fp16ModulesNeedOnlySixteenBitStorage) {
    int fp16 = 0, compensated = 0;
    for (const std::string& name : vk::shader_names()) {
        const vk::KernelInterface k = vk::reflect_kernel(vk::shader_spirv(name));
        EXPECT_FALSE(k.float16_arithmetic) << name;
        fp16 += name.find("_fp16") != std::string::npos;
        const bool dot2 = name.rfind("dwt_", 0) == 0 || name.rfind("lift_", 0) == 0;
        if (name.find("_f64") == std::string::npos) {
            EXPECT_EQ(k.splits_products, dot2) << name;
        }
        compensated += k.splits_products;
        EXPECT_GT(k.invocations, 0u) << name;
        EXPECT_LE(k.invocations, 256u) << name;  // the phone profile's limit
    }
    EXPECT_GT(fp16, 20);
    EXPECT_GT(compensated, 8);
}

// Which buffers a kernel writes, read from its stores and atomics: the
// recorder's barriers follow it.
TEST(KernelInterface, WrittenBuffersAreThoseStoredTo) {
    // pack.comp: src, src4 read; image, image_quads written.
    EXPECT_EQ(vk::reflect_kernel(vk::shader_spirv("pack")).written, 0b1100u);
    // change_detect.comp: frames, means, noise, previous read; scores and statics by atomicMax.
    const vk::KernelInterface detect = vk::reflect_kernel(vk::shader_spirv("change_detect"));
    EXPECT_EQ(detect.bindings, 6u);
    EXPECT_EQ(detect.written, 0b101000u);
    for (const std::string& name : vk::shader_names()) {
        const vk::KernelInterface k = vk::reflect_kernel(vk::shader_spirv(name));
        if (k.bindings > 0) {
            EXPECT_NE(k.written, 0u) << name << " writes nothing";
        }
        EXPECT_EQ(k.written >> k.bindings, 0u) << name;
    }
}

TEST(KernelInterface, RejectsWordsThatAreNotSpirv) {
    const std::uint32_t words[] = {1, 2, 3, 4, 5, 6};
    EXPECT_THROW(vk::reflect_kernel(words), Error);
    EXPECT_THROW(vk::reflect_kernel({}), Error);
}

}  // namespace
}  // namespace vkfuse::test

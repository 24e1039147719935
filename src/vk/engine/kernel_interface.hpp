// What a kernel's SPIR-V says it takes: its descriptor bindings and the size of
// its push-constant block. Recorder::dispatch checks every dispatch against it,
// so a kernel's GLSL declaration (shaders/bindings.glsl's BUFFERS list, its
// Push block) and what the C++ side passes can never drift apart unnoticed:
// every test that records the kernel fails first.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vkfuse::vk {

// constant_id of compensated.glsl's SPLIT_PRODUCTS, which the context sets
// for every pipeline.
inline constexpr std::uint32_t kSplitProductsConstant = 100;

// The scalar types a push-constant member may have.
enum class PushType : std::uint8_t { U32, I32, F32, Address, Other };
std::string_view to_string(PushType);  // "uint", "int", "float", "buffer address", "another type"

// One member of a kernel's push-constant block, as its SPIR-V declares it.
struct PushMember {
    std::string name;  // the GLSL member name ("" where the module carries no names)
    PushType type = PushType::Other;
    std::uint32_t offset = 0;  // bytes from the block's start
};

struct KernelInterface {
    std::uint32_t bindings = 0;    // storage buffers of set 0 (bindings 0 .. n-1)
    std::uint32_t push_bytes = 0;  // end of the push-constant block's last member
    std::uint32_t invocations = 0;  // per workgroup: its local size x * y * z
    std::array<std::uint32_t, 3> local_size{};  // the workgroup's x, y, z
    std::vector<PushMember> push;  // the push-constant block's members, in order
    bool splits_products = false;   // declares SPLIT_PRODUCTS: a compensated float32 kernel
    bool float16_arithmetic = false;  // declares the Float16 capability (shaderFloat16)
    // Bit b set: binding b is written (a store or an atomic reaches it); the
    // rest are only read. Read from the bound variant; the addressed one takes
    // the same buffers in the same order.
    std::uint32_t written = 0;
};

// Reads the interface from SPIR-V words. Throws Error(Device) on words that
// are not SPIR-V or bindings that are not 0 .. n-1.
KernelInterface reflect_kernel(std::span<const std::uint32_t> spirv);

}  // namespace vkfuse::vk

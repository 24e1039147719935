// Push-constant blocks built field by field in std430 order, so each kernel's
// GLSL `Push` block is the only declaration of its layout.
#pragma once
#include <array>
#include <cstdint>
#include <cstring>

#include "vk/api.hpp"

namespace vkfuse::vk {

class PushConstants {
public:
    PushConstants& ptr(VkDeviceAddress address) {  // a buffer_reference: 8-byte aligned
        size_ = (size_ + 7) & ~std::size_t(7);
        return put(&address, sizeof address);
    }
    PushConstants& u32(std::uint32_t v) { return put(&v, sizeof v); }
    PushConstants& i32(std::int32_t v) { return put(&v, sizeof v); }
    PushConstants& f32(float v) { return put(&v, sizeof v); }
    PushConstants& append(const PushConstants& more) { return put(more.data(), more.size()); }
    const void* data() const { return bytes_.data(); }
    std::uint32_t size() const { return std::uint32_t(size_); }

private:
    std::array<std::uint8_t, 128> bytes_{};
    std::size_t size_ = 0;

    PushConstants& put(const void* v, std::size_t n);
};

}  // namespace vkfuse::vk

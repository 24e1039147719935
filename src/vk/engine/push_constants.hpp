// Push-constant blocks built field by field in std430 order, each field named
// as the kernel's GLSL `Push` block names it: Recorder::dispatch checks every
// name, type and offset against the kernel's SPIR-V (kernel_interface.hpp), so
// the GLSL block stays the one declaration of its layout.
#pragma once
#include <array>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>

#include "vk/engine/api.hpp"
#include "vk/engine/kernel_interface.hpp"

namespace vkfuse::vk {

class PushConstants {
public:
    struct Field {
        std::string_view name;  // a string literal: the GLSL member's name
        PushType type = PushType::Other;
        std::uint32_t offset = 0;
    };

    // A buffer_reference (8-byte aligned). Recorder::dispatch pushes the
    // buffers of an addressed kernel itself, unnamed: they are checked by
    // type and place, their names being the kernel's BUFFERS list.
    PushConstants& ptr(std::string_view name, VkDeviceAddress address) {
        size_ = (size_ + 7) & ~std::size_t(7);
        return put(name, PushType::Address, &address, sizeof address);
    }
    PushConstants& u32(std::string_view name, std::uint32_t v) { return put(name, PushType::U32, &v, sizeof v); }
    PushConstants& i32(std::string_view name, std::int32_t v) { return put(name, PushType::I32, &v, sizeof v); }
    PushConstants& f32(std::string_view name, float v) { return put(name, PushType::F32, &v, sizeof v); }
    PushConstants& append(const PushConstants& more);
    const void* data() const { return bytes_.data(); }
    std::uint32_t size() const { return std::uint32_t(size_); }
    std::span<const Field> fields() const { return {fields_.data(), count_}; }

private:
    std::array<std::uint8_t, 128> bytes_{};
    std::size_t size_ = 0;
    std::array<Field, 40> fields_{};
    std::size_t count_ = 0;

    PushConstants& put(std::string_view name, PushType type, const void* v, std::size_t n);
};

}  // namespace vkfuse::vk

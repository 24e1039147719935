// PushConstants (vk/engine/push_constants.hpp): fields packed in std430 order, each remembered by name.
#include "vk/engine/push_constants.hpp"

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {

PushConstants& PushConstants::put(std::string_view name, PushType type, const void* v, std::size_t n) {
    if (size_ + n > bytes_.size() || count_ == fields_.size())
        throw Error(ErrorKind::Device, "internal: push constants exceed 128 bytes");
    fields_[count_++] = {name, type, std::uint32_t(size_)};
    std::memcpy(bytes_.data() + size_, v, n);
    size_ += n;
    return *this;
}

PushConstants& PushConstants::append(const PushConstants& more) {
    for (const Field& f : more.fields()) {
        const std::size_t n = f.type == PushType::Address ? 8 : 4;
        if (f.type == PushType::Address) size_ = (size_ + 7) & ~std::size_t(7);
        put(f.name, f.type, static_cast<const std::uint8_t*>(more.data()) + f.offset, n);
    }
    return *this;
}

}  // namespace vkfuse::vk

// DeviceMemory (vkfuse/vk/interop.hpp): buffers whose memory is shared with
// another device or process (an opaque fd) or with the host (a pointer).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "vk/engine/buffer.hpp"
#include "vk/engine/context_impl.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/vk/interop.hpp"

namespace vkfuse {

struct DeviceMemory::Impl {
    vk::Buffer buffer;
    VkDeviceSize allocation = 0;
    bool exportable = false;
    Context::Impl* ctx = nullptr;
    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl() {
        if (ctx && buffer.handle()) ctx->note_system_memory(buffer.handle(), false);
    }
};

namespace {

void need(bool has, const Context::Impl& ctx, const char* extension, const char* what) {
    if (!has)
        throw Error(ErrorKind::Device, ctx.info.name + ": " + what + " needs " + extension +
                                           ", which this device (or its creator) did not enable");
}

// A buffer of bytes shareable as handle_type, bound to memory of `allocation`
// bytes (0: what the buffer needs) allocated with `import` (an import
// structure, or an export one) chained in front of the device-address flag,
// among allowed_types. allocation 0 is an export (memory made here), any
// other size an import. *allocated_memory is set once Vulkan holds the
// memory (and with it an imported fd). Throws naming `what`.
// visible_types: the (visible) memory types acceptable beside those.
vk::Buffer make_buffer(Context::Impl& ctx, VkDeviceSize bytes, VkExternalMemoryHandleTypeFlagBits handle_type,
                       const void* import, VkDeviceSize allocation, std::uint32_t allowed_types,
                       const std::string& what, VkDeviceSize* allocated, void* host_pointer = nullptr,
                       bool* allocated_memory = nullptr, std::uint32_t visible_types = ~0u) {
    if (bytes == 0) throw Error(ErrorKind::InvalidArgument, what + ": 0 bytes");
    const vk::Api& api = *ctx.api;
    // Memory shared through this handle type must suit such a buffer; a
    // driver that shares it only as a dedicated allocation is refused rather
    // than given memory it cannot take.
    VkPhysicalDeviceExternalBufferInfo query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_BUFFER_INFO};
    query.usage = vk::Buffer::usage(ctx);
    query.handleType = handle_type;
    VkExternalBufferProperties external_props{VK_STRUCTURE_TYPE_EXTERNAL_BUFFER_PROPERTIES};
    api.vkGetPhysicalDeviceExternalBufferProperties(ctx.physical, &query, &external_props);
    const VkExternalMemoryFeatureFlags features = external_props.externalMemoryProperties.externalMemoryFeatures;
    const VkExternalMemoryFeatureFlags wanted =
        allocation == 0 ? VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT : VK_EXTERNAL_MEMORY_FEATURE_IMPORTABLE_BIT;
    if (!(features & wanted) || (features & VK_EXTERNAL_MEMORY_FEATURE_DEDICATED_ONLY_BIT))
        throw Error(ErrorKind::Device, what + ": " + ctx.info.name + " does not share storage buffers' memory this way" +
                                           ((features & VK_EXTERNAL_MEMORY_FEATURE_DEDICATED_ONLY_BIT)
                                                ? " (only as dedicated allocations)"
                                                : ""));
    VkExternalMemoryBufferCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
    external.handleTypes = VkExternalMemoryHandleTypeFlags(handle_type);
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.pNext = &external;
    bci.size = bytes;
    bci.usage = vk::Buffer::usage(ctx);
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    vk::check(api.vkCreateBuffer(ctx.device, &bci, nullptr, &buffer), (what + ": vkCreateBuffer").c_str());
    VkDeviceMemory memory = VK_NULL_HANDLE;
    std::uint32_t mai_type = 0;
    try {
        VkMemoryRequirements req{};
        api.vkGetBufferMemoryRequirements(ctx.device, buffer, &req);
        if (allocation == 0) allocation = req.size;
        if (allocation < req.size)
            throw Error(ErrorKind::InvalidArgument, what + ": " + std::to_string(allocation) +
                                                        " bytes of memory hold no buffer of " + std::to_string(bytes) +
                                                        " bytes (it needs " + std::to_string(req.size) + ")");
        if ((req.memoryTypeBits & allowed_types) == 0)
            throw Error(ErrorKind::Device, what + ": no memory type serves both the buffer and the shared memory");
        VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
        flags.pNext = import;
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        mai.pNext = ctx.device_addresses ? static_cast<const void*>(&flags) : import;
        mai.allocationSize = allocation;
        // Device-local wherever the allowed types have it (a GPU's first type
        // may be system memory); host-visible too where the device has both
        // (lavapipe, integrated GPUs): the host then sees the memory as well.
        const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        const auto& memory_props = ctx.memory_types.properties();
        const std::uint32_t types = ctx.memory_types.visible_bits(req.memoryTypeBits & allowed_types) & visible_types;
        if (types == 0)
            throw Error(ErrorKind::Device, what + ": no memory type serves both the buffer and the shared memory");
        mai.memoryTypeIndex =  // types is not empty: the last preference takes any
            ctx.memory_types.ranked(types, {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | host, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0})
                .front();
        mai_type = mai.memoryTypeIndex;
        vk::check(ctx.memory_types.allocate(api, ctx.device, mai, &memory), (what + ": vkAllocateMemory").c_str());
        if (allocated_memory) *allocated_memory = true;
        vk::check(api.vkBindBufferMemory(ctx.device, buffer, memory, 0), (what + ": vkBindBufferMemory").c_str());
        void* mapped = host_pointer;  // imported host memory is seen where it lies
        const bool visible = (memory_props.memoryTypes[mai.memoryTypeIndex].propertyFlags & host) == host;
        if (visible && !host_pointer) {
            vk::check(api.vkMapMemory(ctx.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), (what + ": vkMapMemory").c_str());
            vk::check_mapping_backed(mapped, allocation, what);
        }
        *allocated = allocation;
        return vk::Buffer::adopt(ctx, buffer, memory, mai.memoryTypeIndex, allocation, bytes, mapped);
    } catch (...) {
        if (memory) ctx.memory_types.free(api, ctx.device, memory, mai_type, allocation);
        api.vkDestroyBuffer(ctx.device, buffer, nullptr);
        throw;
    }
}

}  // namespace

DeviceMemory::DeviceMemory(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceMemory::~DeviceMemory() = default;
DeviceMemory::DeviceMemory(DeviceMemory&&) noexcept = default;
DeviceMemory& DeviceMemory::operator=(DeviceMemory&&) noexcept = default;

DeviceMemory DeviceMemory::allocate_exportable(Context& context, VkDeviceSize bytes) {
    Context::Impl& ctx = vk::ContextAccess::of(context);
    need(ctx.info.external_memory_fd, ctx, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME, "exportable memory");
    VkExportMemoryAllocateInfo exported{VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO};
    exported.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    auto impl = std::make_unique<Impl>();
    impl->ctx = &ctx;
    impl->exportable = true;
    impl->buffer = make_buffer(ctx, bytes, VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT, &exported, 0, ~0u,
                               "exportable memory", &impl->allocation);
    return DeviceMemory(std::move(impl));
}

DeviceMemory DeviceMemory::import_fd(Context& context, int fd, VkDeviceSize bytes) {
    Context::Impl& ctx = vk::ContextAccess::of(context);
    need(ctx.info.external_memory_fd, ctx, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME, "importing an fd");
    if (fd < 0) throw Error(ErrorKind::InvalidArgument, "import_fd: fd " + std::to_string(fd) + " is not open");
    // Vulkan takes the fd it imports, even where a later step (binding,
    // mapping) then fails and frees the memory: it imports a duplicate, so
    // the caller's fd stays theirs until everything has succeeded.
    const int copy = ::fcntl(fd, F_DUPFD_CLOEXEC, 0);
    if (copy < 0)
        throw Error(ErrorKind::InvalidArgument, "import_fd: fd " + std::to_string(fd) + ": " + std::strerror(errno));
    VkImportMemoryFdInfoKHR imported{VK_STRUCTURE_TYPE_IMPORT_MEMORY_FD_INFO_KHR};
    imported.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    imported.fd = copy;
    auto impl = std::make_unique<Impl>();
    impl->ctx = &ctx;
    bool vulkan_took_it = false;
    try {
        // An opaque fd's memory is imported whole: the exporter's allocation
        // size, and the buffer spans it.
        impl->buffer = make_buffer(ctx, bytes, VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT, &imported, bytes, ~0u,
                                   "import_fd", &impl->allocation, nullptr, &vulkan_took_it);
    } catch (...) {
        if (!vulkan_took_it) ::close(copy);
        throw;
    }
    ::close(fd);  // the import succeeded: as with a plain import, the fd is used up
    return DeviceMemory(std::move(impl));
}

VkDeviceSize DeviceMemory::host_pointer_alignment(Context& context) {
    Context::Impl& ctx = vk::ContextAccess::of(context);
    if (!ctx.info.external_memory_host) return 0;
    VkPhysicalDeviceExternalMemoryHostPropertiesEXT host{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &host;
    ctx.api->vkGetPhysicalDeviceProperties2(ctx.physical, &props);
    return host.minImportedHostPointerAlignment;
}

DeviceMemory DeviceMemory::import_host(Context& context, void* pointer, VkDeviceSize bytes) {
    Context::Impl& ctx = vk::ContextAccess::of(context);
    need(ctx.info.external_memory_host, ctx, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME, "importing host memory");
    const VkDeviceSize alignment = host_pointer_alignment(context);
    if (!pointer || reinterpret_cast<std::uintptr_t>(pointer) % alignment != 0 || bytes % alignment != 0)
        throw Error(ErrorKind::InvalidArgument, "import_host: pointer and size (" + std::to_string(bytes) +
                                                    " bytes) must be multiples of " + std::to_string(alignment));
    const auto handle = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
    VkMemoryHostPointerPropertiesEXT props{VK_STRUCTURE_TYPE_MEMORY_HOST_POINTER_PROPERTIES_EXT};
    vk::check(ctx.api->vkGetMemoryHostPointerPropertiesEXT(ctx.device, handle, pointer, &props),
              "import_host: vkGetMemoryHostPointerPropertiesEXT");
    VkImportMemoryHostPointerInfoEXT imported{VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT};
    imported.handleType = handle;
    imported.pHostPointer = pointer;
    auto impl = std::make_unique<Impl>();
    impl->ctx = &ctx;
    // A discrete GPU imports host memory into system memory only: so does
    // a simulated one (vk/engine/memory_types.hpp), whose types all share one real type.
    std::uint32_t system_types = ~0u;
    if (ctx.memory_types.simulated()) {
        const auto& memory = ctx.memory_types.properties();
        system_types = 0;
        for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
            if (!(memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) system_types |= 1u << i;
    }
    impl->buffer = make_buffer(ctx, bytes, handle, &imported, bytes, props.memoryTypeBits, "import_host",
                               &impl->allocation, pointer, nullptr, system_types);
    ctx.note_system_memory(impl->buffer.handle(), !impl->buffer.device_local() && ctx.memory_types.has_device_local());
    return DeviceMemory(std::move(impl));
}

int DeviceMemory::export_fd() const {
    if (!impl_->exportable)
        throw Error(ErrorKind::InvalidArgument, "export_fd: only allocate_exportable() memory can be exported");
    Context::Impl& ctx = *impl_->ctx;
    VkMemoryGetFdInfoKHR info{VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR};
    info.memory = impl_->buffer.memory();
    info.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    int fd = -1;
    vk::check(ctx.api->vkGetMemoryFdKHR(ctx.device, &info, &fd), "export_fd: vkGetMemoryFdKHR");
    return fd;
}

BufferRange DeviceMemory::range() const { return {impl_->buffer.handle(), 0, impl_->buffer.size()}; }
VkDeviceSize DeviceMemory::size() const { return impl_->allocation; }
void* DeviceMemory::mapped() const { return impl_->buffer.mapped(); }

}  // namespace vkfuse

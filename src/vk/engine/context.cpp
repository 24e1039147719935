#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "vk/engine/context_impl.hpp"
#include "vk/engine/device_info.hpp"
#include "vk/engine/fma_probe.hpp"
#include "vk/engine/shader_registry.hpp"
#include "vk/engine/spirv_subnormals.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT types,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* impl = static_cast<Context::Impl*>(user);
    // Count validation-type messages of warning or error severity: those are
    // what tests fail on. Info/verbose chatter (e.g. loader notes) is ignored.
    const bool counts = (types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT) &&
                        severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    if (!counts) return VK_FALSE;
    impl->validation_messages.fetch_add(1);
    std::string text = data && data->pMessage ? data->pMessage : "(no message)";
    if (impl->on_validation_message)
        impl->on_validation_message(text);
    else
        std::fprintf(stderr, "vkfuse: Vulkan validation: %s\n", text.c_str());
    return VK_FALSE;
}

// The choice an environment variable names, T::Auto where it is unset or
// empty; any other text is refused in one line naming the variable.
template <class T>
T choice_from_environment(const char* variable, std::optional<T> (*parse)(std::string_view), const char* expected) {
    const char* env = std::getenv(variable);
    if (!env || !*env) return T::Auto;
    const std::optional<T> parsed = parse(env);
    if (!parsed)
        throw Error(ErrorKind::InvalidArgument,
                    std::string(variable) + "=" + std::string(env).substr(0, 40) + ": expected " + expected);
    return *parsed;
}

FilterArithmetic arithmetic_from_environment() {
    return choice_from_environment("VKFUSE_FILTER_ARITHMETIC", parse_filter_arithmetic,
                                   "auto, float64 or compensated-float32");
}

KernelBuffers kernel_buffers_from_environment() {
    return choice_from_environment("VKFUSE_KERNEL_BUFFERS", parse_kernel_buffers, "auto, bound or addresses");
}

// VKFUSE_DEVICE_PROFILE's profile, null where unset.
const vk::DeviceProfile* profile_from_environment() {
    const char* env = std::getenv("VKFUSE_DEVICE_PROFILE");
    return env && *env ? &vk::find_device_profile(env, "VKFUSE_DEVICE_PROFILE") : nullptr;
}

bool has_layer(const vk::Api& api, const char* name) {
    std::uint32_t n = 0;
    api.vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    api.vkEnumerateInstanceLayerProperties(&n, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

}  // namespace

Context::Impl::Impl(const ContextOptions& options)
    : device_addresses_only(options.device_addresses_only), on_validation_message(options.on_validation_message),
      split_requested_(options.split_products) {
    api = vk::Api::load();
    // VKFUSE_VALIDATION=1 turns the layer on for any program, =sync with
    // synchronization validation (the CLI in tests).
    const char* env = std::getenv("VKFUSE_VALIDATION");
    const bool sync = options.synchronization_validation || (env && std::strcmp(env, "sync") == 0);
    const bool validation = options.validation || sync || (env && std::strcmp(env, "1") == 0);
    try {
        create_instance(validation, sync);
        choose_device(options.device_index);
        apply_profile(options.device_profile);
        if (device_addresses_only && !device_addresses)
            throw Error(ErrorKind::Device, info.name + ": device_addresses_only asked for, but the device has no "
                                                       "bufferDeviceAddress");
        choose_filter_arithmetic(options.filter_arithmetic);
        choose_kernel_buffers(options.kernel_buffers);
        create_device();
        create_layout();
        open_pipeline_cache(options.pipeline_cache);
    } catch (...) {
        release();  // members' destructors will not run release() for a throwing constructor
        throw;
    }
}

Context::Impl::Impl(const CallerDevice& caller, const ContextOptions& options)
    : owns_device(false), device_addresses_only(options.device_addresses_only), split_requested_(options.split_products) {
    if (!caller.instance || !caller.physical_device || !caller.device)
        throw Error(ErrorKind::InvalidArgument, "caller device: instance, physical device and device must all be given");
    api = vk::Api::adopt(caller.get_instance_proc_addr);
    try {
        instance = caller.instance;
        api->load_instance(instance);
        const auto devices = vk::enumerate_devices(*api, instance);
        const auto it = std::find_if(devices.begin(), devices.end(),
                                     [&](const auto& d) { return d.handle == caller.physical_device; });
        if (it == devices.end())
            throw Error(ErrorKind::InvalidArgument, "caller device: the physical device is not one of the instance's");
        if (!it->info.usable) throw Error(ErrorKind::Device, "caller device " + it->info.name + ": " + it->info.why_not);
        physical = caller.physical_device;
        info = it->info;
        denorm_preserve = it->denorm_preserve;  // a property: nothing for the caller to enable
        // What the device has counts only where the caller enabled it.
        info.fp16_storage = info.fp16_storage && caller.fp16_storage;
        info.float64 = info.float64 && caller.shader_float64;
        info.external_memory_fd = info.external_memory_fd && caller.external_memory_fd;
        info.external_memory_host = info.external_memory_host && caller.external_memory_host;
        api->vkGetPhysicalDeviceProperties(physical, &properties);
        VkPhysicalDeviceMemoryProperties memory{};
        api->vkGetPhysicalDeviceMemoryProperties(physical, &memory);
        memory_types.use_device(memory);
        // The caller enabled what its device has; vkfuse uses device
        // addresses only where the caller's device creation enabled them.
        device_addresses = info.device_addresses && caller.buffer_device_address;
        choose_filter_arithmetic(options.filter_arithmetic);
        choose_kernel_buffers(options.kernel_buffers);
        std::uint32_t n = 0;
        api->vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, nullptr);
        std::vector<VkQueueFamilyProperties> families(n);
        api->vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, families.data());
        if (caller.queue_family >= n || !(families[caller.queue_family].queueFlags & VK_QUEUE_COMPUTE_BIT))
            throw Error(ErrorKind::InvalidArgument, "caller device: queue family " + std::to_string(caller.queue_family) +
                                                        " has no compute queue");
        if (caller.queue_index >= families[caller.queue_family].queueCount)
            throw Error(ErrorKind::InvalidArgument, "caller device: queue index " + std::to_string(caller.queue_index) +
                                                        " is beyond the " +
                                                        std::to_string(families[caller.queue_family].queueCount) +
                                                        " queues of family " + std::to_string(caller.queue_family));
        queue_family = caller.queue_family;
        timestamp_bits = families[queue_family].timestampValidBits;
        device = caller.device;
        api->load_device(device);
        api->vkGetDeviceQueue(device, queue_family, caller.queue_index, &queue);
        if (!queue)
            throw Error(ErrorKind::InvalidArgument, "caller device: queue index " +
                                                        std::to_string(caller.queue_index) + " of family " +
                                                        std::to_string(queue_family) +
                                                        " was not created with the device");
        create_layout();
        open_pipeline_cache(options.pipeline_cache);
    } catch (...) {
        release();
        throw;
    }
}

void Context::Impl::create_instance(bool validation, bool synchronization_validation) {
    std::uint32_t version = VK_API_VERSION_1_0;
    if (api->vkEnumerateInstanceVersion) api->vkEnumerateInstanceVersion(&version);
    if (version < VK_API_VERSION_1_2)
        throw Error(ErrorKind::Device, "Vulkan loader supports only API " + vk::version_string(version) +
                                           ", vkfuse needs 1.2");
    if (validation && !has_layer(*api, kValidationLayer))
        throw Error(ErrorKind::Device, "validation requested but VK_LAYER_KHRONOS_validation is not installed "
                                       "(install vulkan-validationlayers)");
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vkfuse";
    app.pEngineName = "vkfuse";
    app.apiVersion = VK_API_VERSION_1_2;
    std::vector<const char*> layers, extensions;
    if (validation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    // The layer itself offers VK_EXT_validation_features, which turns its
    // synchronization validation on.
    const VkValidationFeatureEnableEXT sync_feature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync_feature;
    const bool sync = validation && synchronization_validation;
    if (sync) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    dbg.pfnUserCallback = on_debug_message;
    dbg.pUserData = this;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pNext = validation ? &dbg : nullptr;  // also catches create/destroy-instance messages
    if (sync) dbg.pNext = &features;
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = std::uint32_t(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = std::uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    vk::check(api->vkCreateInstance(&ci, nullptr, &instance), "vkCreateInstance");
    api->load_instance(instance);
    dbg.pNext = nullptr;  // the features belong to the instance alone
    if (validation)
        vk::check(api->vkCreateDebugUtilsMessengerEXT(instance, &dbg, nullptr, &messenger),
                  "vkCreateDebugUtilsMessengerEXT");
}

void Context::Impl::choose_device(int index) {
    auto devices = vk::enumerate_devices(*api, instance);
    if (devices.empty()) throw Error(ErrorKind::Device, "no Vulkan device found (is mesa-vulkan-drivers installed?)");
    const vk::PhysicalDeviceEntry* chosen = nullptr;
    if (index >= 0) {
        if (index >= int(devices.size()))
            throw Error(ErrorKind::Device, "Vulkan device " + std::to_string(index) + " does not exist (" +
                                               std::to_string(devices.size()) + " found)");
        chosen = &devices[std::size_t(index)];
        if (!chosen->info.usable)
            throw Error(ErrorKind::Device, "Vulkan device " + std::to_string(index) + " (" + chosen->info.name +
                                               ") is not usable: " + chosen->info.why_not);
    } else {
        chosen = vk::best_device(devices);
        if (!chosen)
            throw Error(ErrorKind::Device, "no usable Vulkan device: " + devices.front().info.name + ": " +
                                               devices.front().info.why_not);
    }
    physical = chosen->handle;
    info = chosen->info;
    memory_budget = chosen->memory_budget;
    denorm_preserve = chosen->denorm_preserve;
    device_addresses = info.device_addresses;
    api->vkGetPhysicalDeviceProperties(physical, &properties);
    VkPhysicalDeviceMemoryProperties memory{};
    api->vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    memory_types.use_device(memory);
}

void Context::Impl::apply_profile(const std::string& wanted) {
    profile = wanted.empty() ? profile_from_environment() : &vk::find_device_profile(wanted, "device profile");
    if (!profile) return;
    vk::apply_limits(*profile, properties.limits);
    if (profile->discrete_memory) {
        const VkPhysicalDeviceMemoryProperties real = memory_types.properties();  // choose_device's, a copy
        memory_types.simulate_discrete(real);
    }
    if (!profile->device_addresses) device_addresses = false;
    info.device_addresses = device_addresses;
    if (profile->flushes_subnormals) info.float32_subnormals = false;
    adapted("device profile " + std::string(profile->name) + " (simulated on " + info.name + "): " +
            std::string(profile->summary));
}

// Auto takes doubles where they are native vector lanes: on a CPU device one
// double fma per tap is cheaper than Dot2's ten float operations
// (docs/architecture.md has the measurement). A GPU's double rate is often a
// small fraction of its float rate, so GPUs keep Dot2.
void Context::Impl::choose_filter_arithmetic(FilterArithmetic wanted) {
    if (wanted == FilterArithmetic::Auto) wanted = arithmetic_from_environment();
    if (wanted == FilterArithmetic::Float64 && !info.float64)
        throw Error(ErrorKind::Device, info.name + ": float64 filter arithmetic asked for, but the device has no "
                                                   "shaderFloat64");
    if (wanted == FilterArithmetic::Auto)
        wanted = info.float64 && info.type == "cpu" ? FilterArithmetic::Float64 : FilterArithmetic::CompensatedFloat32;
    filter_arithmetic = wanted;
}

// Auto takes addresses on a CPU device: on lavapipe the same kernels ran a
// fifth to a quarter faster through device addresses than bound, although a
// plain copy costs the two alike (docs/measurements.md). GPUs keep bindings,
// the path their drivers are built around. device_addresses_only implies
// Addresses, whatever was asked.
void Context::Impl::choose_kernel_buffers(KernelBuffers wanted) {
    if (device_addresses_only) wanted = KernelBuffers::Addresses;
    if (wanted == KernelBuffers::Auto) wanted = kernel_buffers_from_environment();
    if (wanted == KernelBuffers::Addresses && !device_addresses)
        throw Error(ErrorKind::Device, info.name + ": kernel buffers through addresses asked for, but the device has no "
                                                   "bufferDeviceAddress");
    if (wanted == KernelBuffers::Auto)
        wanted = device_addresses && info.type == "cpu" ? KernelBuffers::Addresses : KernelBuffers::Bound;
    kernel_buffers = wanted;
}

bool Context::Impl::products_split() {
    std::lock_guard lock(products_mutex_);
    if (split_state_ >= 0) return split_state_ == 1;
    bool split = false;
    if (filter_arithmetic == FilterArithmetic::CompensatedFloat32) {
        split = split_requested_ || !vk::fma_is_fused(*this);
        if (split)
            adapted(std::string(split_requested_ ? "asked to split products" : "fma is not fused") +
                    ": compensated float32 filters take each product's error from Dekker's split");
    }
    split_state_ = split ? 1 : 0;
    return split;
}

void Context::Impl::create_device() {
    std::uint32_t n = 0;
    api->vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    api->vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, families.data());
    bool found = false;
    for (std::uint32_t i = 0; i < n && !found; ++i)
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
            queue_family = i;
            timestamp_bits = families[i].timestampValidBits;
            found = true;
        }
    if (!found) throw Error(ErrorKind::Device, info.name + ": no compute queue");
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = queue_family;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.bufferDeviceAddress = device_addresses ? VK_TRUE : VK_FALSE;
    f12.timelineSemaphore = VK_TRUE;  // required of every Vulkan 1.2 device: vkfuse::submit signals one
    // The _fp16 kernels' float16 planes (storage only: loads and stores
    // convert, so shaderFloat16 is not needed), enabled where the device has them.
    f11.storageBuffer16BitAccess = info.fp16_storage;
    f12.pNext = &f11;
    // The _f64 kernels' doubles, enabled only when the context uses them.
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.features.shaderFloat64 = filter_arithmetic == FilterArithmetic::Float64 ? VK_TRUE : VK_FALSE;
    f2.pNext = &f12;
    // Shared memory (vk/interop.hpp), enabled where the device has it.
    std::vector<const char*> extensions;
    if (info.external_memory_fd) extensions.push_back(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    if (info.external_memory_host) extensions.push_back(VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);
    // Heap budgets (Context::memory_heaps), where the device reports them.
    if (memory_budget) extensions.push_back(VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = &f2;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = std::uint32_t(extensions.size());
    dci.ppEnabledExtensionNames = extensions.data();
    vk::check(api->vkCreateDevice(physical, &dci, nullptr, &device), "vkCreateDevice");
    api->load_device(device);
    api->vkGetDeviceQueue(device, queue_family, 0, &queue);
}

void Context::Impl::create_layout() {
    bound_buffers = std::min(kMaxKernelBuffers, properties.limits.maxPerStageDescriptorStorageBuffers);
    if (bound_buffers < kMaxKernelBuffers) {
        if (!device_addresses)
            throw Error(ErrorKind::Device, info.name + ": " + std::to_string(bound_buffers) +
                                               " storage buffers per stage and no bufferDeviceAddress: vkfuse's "
                                               "kernels bind up to " + std::to_string(kMaxKernelBuffers));
        adapted("kernels binding more than " + std::to_string(bound_buffers) +
                " storage buffers (maxPerStageDescriptorStorageBuffers) reach them through device addresses");
    }
    if (!device_addresses)
        adapted("no bufferDeviceAddress: every kernel binds its buffers, and plans beyond maxStorageBufferRange run "
                "in blocks of sensors");
    if (memory_types.simulated())
        adapted("uploads take the " + memory_types.describe_heap(2) + " while it has room, then system memory; "
                "read-back memory is cached, not coherent, and invalidated before each read");
    VkDescriptorSetLayoutBinding bindings[kMaxKernelBuffers]{};
    for (std::uint32_t b = 0; b < bound_buffers; ++b)
        bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = bound_buffers;
    lci.pBindings = bindings;
    vk::check(api->vkCreateDescriptorSetLayout(device, &lci, nullptr, &set_layout), "vkCreateDescriptorSetLayout");
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, kPushConstantBytes};
    VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    ci.setLayoutCount = 1;
    ci.pSetLayouts = &set_layout;
    ci.pushConstantRangeCount = 1;
    ci.pPushConstantRanges = &range;
    vk::check(api->vkCreatePipelineLayout(device, &ci, nullptr, &layout), "vkCreatePipelineLayout");
}

VkPipeline Context::Impl::pipeline(const std::string& shader, std::span<const std::uint32_t> specialization) {
    if (kernel_interface(shader).splits_products) products_split();  // decided before it is built in
    std::lock_guard lock(pipelines_mutex_);
    auto key = std::make_pair(shader, std::vector<std::uint32_t>(specialization.begin(), specialization.end()));
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
    VkPipeline pipe = create_pipeline(shader, layout, specialization);
    pipelines_.emplace(std::move(key), pipe);
    return pipe;
}

const vk::KernelInterface& Context::Impl::kernel_interface(const std::string& shader) {
    std::lock_guard lock(pipelines_mutex_);
    auto it = interfaces_.find(shader);
    if (it == interfaces_.end()) it = interfaces_.emplace(shader, vk::reflect_kernel(vk::shader_spirv(shader))).first;
    return it->second;
}

void Context::Impl::use_kernel_interface(const std::string& shader, vk::KernelInterface k) {
    std::lock_guard lock(pipelines_mutex_);
    interfaces_.insert_or_assign(shader, std::move(k));
}

VkPipeline Context::Impl::create_pipeline(const std::string& shader, VkPipelineLayout with_layout,
                                          std::span<const std::uint32_t> specialization) {
    const std::span<const std::uint32_t> embedded = vk::shader_spirv(shader);
    const std::uint32_t invocations = vk::reflect_kernel(embedded).invocations;
    if (invocations > properties.limits.maxComputeWorkGroupInvocations)
        throw Error(ErrorKind::Device, info.name + ": kernel " + shader + " runs " + std::to_string(invocations) +
                                           " invocations per workgroup; the device allows " +
                                           std::to_string(properties.limits.maxComputeWorkGroupInvocations));
    // Where the device can be asked to, every kernel keeps float32
    // subnormals (vk/engine/spirv_subnormals.hpp).
    const std::vector<std::uint32_t> spirv = denorm_preserve
                                                 ? vk::preserving_subnormals(embedded)
                                                 : std::vector<std::uint32_t>(embedded.begin(), embedded.end());
    VkShaderModuleCreateInfo mci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mci.codeSize = spirv.size() * sizeof(std::uint32_t);
    mci.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    vk::check(api->vkCreateShaderModule(device, &mci, nullptr, &module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo pci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pci.stage.module = module;
    pci.stage.pName = "main";
    // The kernel's own constants (constant_id 0, 1, ...), then the context's.
    std::vector<std::uint32_t> words(specialization.begin(), specialization.end());
    std::vector<VkSpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < words.size(); ++i)
        entries.push_back({i, i * std::uint32_t(sizeof(std::uint32_t)), sizeof(std::uint32_t)});
    entries.push_back({vk::kSplitProductsConstant, std::uint32_t(words.size() * sizeof(std::uint32_t)), sizeof(VkBool32)});
    // Decided by now for every kernel that declares it (pipeline()).
    words.push_back(split_state_ == 1 ? VK_TRUE : VK_FALSE);
    VkSpecializationInfo spec{std::uint32_t(entries.size()), entries.data(), words.size() * sizeof(std::uint32_t),
                              words.data()};
    pci.stage.pSpecializationInfo = &spec;
    pci.layout = with_layout;
    VkPipeline pipe = VK_NULL_HANDLE;
    VkResult r = api->vkCreateComputePipelines(device, pipeline_cache ? pipeline_cache->handle() : VK_NULL_HANDLE, 1,
                                               &pci, nullptr, &pipe);
    api->vkDestroyShaderModule(device, module, nullptr);  // the pipeline keeps what it needs
    vk::check(r, ("vkCreateComputePipelines(" + shader + ")").c_str());
    return pipe;
}

void Context::Impl::note_system_memory(VkBuffer buffer, bool in_system_memory) {
    std::lock_guard lock(system_memory_mutex_);
    if (in_system_memory)
        system_memory_buffers_.insert(buffer);
    else
        system_memory_buffers_.erase(buffer);
}

bool Context::Impl::in_system_memory(VkBuffer buffer) const {
    std::lock_guard lock(system_memory_mutex_);
    return system_memory_buffers_.count(buffer) > 0;
}

void Context::Impl::adapted(const std::string& what) {
    std::lock_guard lock(adaptations_mutex_);
    if (std::find(adaptations_.begin(), adaptations_.end(), what) == adaptations_.end()) adaptations_.push_back(what);
}

std::vector<std::string> Context::Impl::adaptations() const {
    std::lock_guard lock(adaptations_mutex_);
    return adaptations_;
}

void Context::Impl::note_fallback(std::uint32_t wanted, std::uint32_t taken) {
    const std::uint32_t from = memory_types.heap_of(wanted), to = memory_types.heap_of(taken);
    if (from != to) adapted("memory: the " + memory_types.describe_heap(from) + " was full; buffers went to the " +
                            memory_types.describe_heap(to));
}

Context::Impl::~Impl() { release(); }

void Context::Impl::open_pipeline_cache(const std::string& path) {
    std::string file = path;
    if (file.empty())
        if (const char* env = std::getenv("VKFUSE_PIPELINE_CACHE"); env && *env) file = env;
    if (!file.empty()) pipeline_cache = std::make_unique<vk::PipelineCache>(*api, device, properties, file);
}

void Context::Impl::release() {
    // A caller's device may be busy with the caller's own work: vkfuse's
    // submissions were each waited for by the plan that made them.
    if (device && owns_device && api->vkDeviceWaitIdle) api->vkDeviceWaitIdle(device);
    pipeline_cache.reset();  // written back to its file, if it grew
    if (device && api->vkDestroyPipeline) {  // null only where loading the device's entry points failed
        for (auto& [name, pipe] : pipelines_) api->vkDestroyPipeline(device, pipe, nullptr);
        if (layout) api->vkDestroyPipelineLayout(device, layout, nullptr);
        if (set_layout) api->vkDestroyDescriptorSetLayout(device, set_layout, nullptr);
    }
    if (device && owns_device && api->vkDestroyDevice) api->vkDestroyDevice(device, nullptr);
    pipelines_.clear();
    set_layout = VK_NULL_HANDLE;
    layout = VK_NULL_HANDLE;
    device = VK_NULL_HANDLE;
    if (messenger) api->vkDestroyDebugUtilsMessengerEXT(instance, messenger, nullptr);
    messenger = VK_NULL_HANDLE;
    if (instance && owns_device) api->vkDestroyInstance(instance, nullptr);
    instance = VK_NULL_HANDLE;
}

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Context::~Context() = default;
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;
std::string_view to_string(FilterArithmetic a) {
    switch (a) {
        case FilterArithmetic::Auto: return "auto";
        case FilterArithmetic::Float64: return "float64";
        case FilterArithmetic::CompensatedFloat32: return "compensated float32";
    }
    return "?";
}

std::string_view to_string(KernelBuffers b) {
    switch (b) {
        case KernelBuffers::Auto: return "auto";
        case KernelBuffers::Bound: return "bound";
        case KernelBuffers::Addresses: return "addresses";
    }
    return "?";
}

std::optional<KernelBuffers> parse_kernel_buffers(std::string_view text) {
    for (KernelBuffers b : {KernelBuffers::Auto, KernelBuffers::Bound, KernelBuffers::Addresses})
        if (text == to_string(b)) return b;
    return std::nullopt;
}

void check_vulkan_environment() {
    arithmetic_from_environment();
    kernel_buffers_from_environment();
    profile_from_environment();
}

bool validation_layer_installed() {
    try {
        return has_layer(*vk::Api::load(), kValidationLayer);
    } catch (const Error&) {
        return false;  // no loader
    }
}

std::optional<FilterArithmetic> parse_filter_arithmetic(std::string_view text) {
    for (FilterArithmetic a : {FilterArithmetic::Auto, FilterArithmetic::Float64, FilterArithmetic::CompensatedFloat32}) {
        std::string name(to_string(a)), dashed = name;
        std::replace(dashed.begin(), dashed.end(), ' ', '-');
        if (text == name || text == dashed) return a;
    }
    return std::nullopt;
}

std::string_view to_string(Backend b) {
    switch (b) {
        case Backend::Cpu: return "cpu";
        case Backend::Vulkan: return "vulkan";
        case Backend::Auto: return "auto";
    }
    return "?";
}

std::optional<Backend> parse_backend(std::string_view text) {
    for (Backend b : {Backend::Cpu, Backend::Vulkan, Backend::Auto})
        if (text == to_string(b)) return b;
    return std::nullopt;
}

std::optional<Context> open_backend(Backend choice, std::string_view subject, std::string* fallback_reason) {
    if (choice == Backend::Cpu) return std::nullopt;
    try {
        return std::optional<Context>(std::in_place);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Device) throw;
        if (choice == Backend::Vulkan)
            throw Error(ErrorKind::Device,
                        std::string(subject) + " vulkan: no usable Vulkan device (" + e.what() + ")");
        if (fallback_reason) *fallback_reason = e.what();
        return std::nullopt;
    }
}

const DeviceInfo& Context::device() const { return impl_->info; }
FilterArithmetic Context::filter_arithmetic() const { return impl_->filter_arithmetic; }
KernelBuffers Context::kernel_buffers() const { return impl_->kernel_buffers; }
bool Context::splits_products() const { return impl_->products_split(); }
std::string Context::device_profile() const { return impl_->profile ? std::string(impl_->profile->name) : ""; }
std::vector<std::string> Context::adaptations() const { return impl_->adaptations(); }
std::string Context::pipeline_cache() const { return impl_->pipeline_cache ? impl_->pipeline_cache->state() : ""; }

std::vector<MemoryHeap> Context::memory_heaps() const {
    const Impl& im = *impl_;
    const auto& memory = im.memory_types.properties();
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budgets{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    const bool with_budget = im.memory_budget && !im.memory_types.simulated() && im.api->vkGetPhysicalDeviceMemoryProperties2;
    if (with_budget) {
        VkPhysicalDeviceMemoryProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
        props.pNext = &budgets;
        im.api->vkGetPhysicalDeviceMemoryProperties2(im.physical, &props);
    }
    std::vector<MemoryHeap> heaps;
    for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h) {
        MemoryHeap heap;
        heap.bytes = memory.memoryHeaps[h].size;
        heap.device_local = memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT;
        heap.host_visible = im.memory_types.host_visible_heap(h);
        heap.vkfuse_bytes = im.memory_types.heap_used(h);
        if (with_budget) {
            heap.budget = budgets.heapBudget[h];
            heap.usage = budgets.heapUsage[h];
        }
        heaps.push_back(heap);
    }
    return heaps;
}

std::vector<std::string> device_profile_names() {
    std::vector<std::string> names;
    for (const vk::DeviceProfile& p : vk::device_profiles()) names.emplace_back(p.name);
    return names;
}
std::uint64_t Context::validation_message_count() const { return impl_->validation_messages.load(); }

}  // namespace vkfuse

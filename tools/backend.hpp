// backend.hpp - which engine a command runs on: the Vulkan path or the CPU reference.
#pragma once
#include <optional>
#include <string_view>

#include "args.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::cli {

enum class BackendChoice { Cpu, Vulkan, Auto };

// The --backend option, the same for every command that computes.
inline constexpr OptionSpec kBackendOption{
    "--backend", "", "B", "cpu, vulkan or auto (default auto: Vulkan when a usable device exists, else cpu)"};

// "cpu", "vulkan" or "auto"; throws Error(InvalidArgument) naming --backend otherwise.
BackendChoice parse_backend(std::string_view text);

// The Vulkan context the choice asks for, or nothing for the CPU reference path.
// Auto falls back to the CPU when no usable device exists and says so in one
// line on stderr; Vulkan without a device throws Error(Device) naming --backend.
std::optional<Context> open_backend(BackendChoice choice);

}  // namespace vkfuse::cli

// backend.hpp - which engine a command runs on: the Vulkan path or the CPU reference.
#pragma once
#include <optional>
#include <string_view>

#include "args.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::cli {

// The --backend option, the same for every command that computes.
inline constexpr OptionSpec kBackendOption{
    "--backend", "", "B", "cpu, vulkan or auto (default auto: Vulkan when a usable device exists, else cpu)"};

// "cpu", "vulkan" or "auto"; throws Error(InvalidArgument) naming --backend otherwise.
Backend parse_backend_option(std::string_view text);

// vkfuse::open_backend for a command: Auto's fallback to the CPU is said in
// one line on stderr; Vulkan without a device throws naming --backend.
std::optional<Context> open_backend(Backend choice);

}  // namespace vkfuse::cli

#include "backend.hpp"

#include <cstdio>
#include <string>

#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {

BackendChoice parse_backend(std::string_view text) {
    if (text == "cpu") return BackendChoice::Cpu;
    if (text == "vulkan") return BackendChoice::Vulkan;
    if (text == "auto") return BackendChoice::Auto;
    throw Error(ErrorKind::InvalidArgument, "--backend " + std::string(text) + ": expected cpu, vulkan or auto");
}

std::optional<Context> open_backend(BackendChoice choice) {
    if (choice == BackendChoice::Cpu) return std::nullopt;
    try {
        return std::optional<Context>(std::in_place);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Device) throw;
        if (choice == BackendChoice::Vulkan)
            throw Error(ErrorKind::Device, std::string("--backend vulkan: no usable Vulkan device (") + e.what() + ")");
        std::fprintf(stderr, "vkfuse: no usable Vulkan device (%s); using the CPU reference path\n", e.what());
        return std::nullopt;
    }
}

}  // namespace vkfuse::cli

#include "backend.hpp"

#include <cstdio>
#include <string>

#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {

Backend parse_backend_option(std::string_view text) {
    if (const std::optional<Backend> b = parse_backend(text)) return *b;
    throw Error(ErrorKind::InvalidArgument, "--backend " + std::string(text) + ": expected cpu, vulkan or auto");
}

std::optional<Context> open_backend(Backend choice) {
    std::string why;
    std::optional<Context> context = vkfuse::open_backend(choice, "--backend", &why);
    if (!context && choice == Backend::Auto)
        std::fprintf(stderr, "vkfuse: no usable Vulkan device (%s); using the CPU reference path\n", why.c_str());
    return context;
}

}  // namespace vkfuse::cli

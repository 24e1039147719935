#include "io/path_component.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "vkfuse/core/error.hpp"

namespace vkfuse::io {
namespace {

constexpr std::size_t kMaxComponentBytes = 255;  // NAME_MAX on Linux file systems

}  // namespace

bool is_plain_component(std::string_view name) {
    if (name.empty() || name.size() > kMaxComponentBytes || name == "." || name == "..") return false;
    for (char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '/' || c == '\\' || c < 0x20 || c == 0x7f) return false;
    }
    return true;
}

std::string printable(std::string_view name) {
    std::string out;
    for (char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 0x20 && c < 0x7f && c != '\\') {
            out += ch;
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            out += hex;
        }
    }
    return out;
}

std::string component_problem(std::string_view name) {
    if (is_plain_component(name)) return {};
    const std::string shown = "\"" + printable(name.substr(0, 80)) + (name.size() > 80 ? "...\"" : "\"");
    if (name.empty()) return shown + ": empty";
    if (name.size() > kMaxComponentBytes) return shown + ": longer than 255 bytes";
    return shown + ": not usable as a file name (one component: no '/', '\\', control characters, '.' or '..')";
}

void check_plain_component(std::string_view name, const std::string& what) {
    const std::string problem = component_problem(name);
    if (!problem.empty()) throw Error(ErrorKind::InvalidArgument, what + " " + problem);
}

bool is_contained_relative_path(std::string_view path) {
    if (path.empty()) return false;
    std::size_t start = 0;
    while (true) {
        const std::size_t slash = path.find('/', start);
        const std::string_view part = path.substr(start, slash == std::string_view::npos ? slash : slash - start);
        if (!is_plain_component(part)) return false;
        if (slash == std::string_view::npos) return true;
        start = slash + 1;
    }
}

std::string resolve_inside(const std::string& base, const std::string& relative) {
    const std::string joined = (std::filesystem::path(base) / relative).string();
    auto real = [](const std::string& p) {
        std::unique_ptr<char, decltype(&std::free)> r(::realpath(p.c_str(), nullptr), &std::free);
        return r ? std::string(r.get()) : std::string();
    };
    const std::string real_base = real(base), real_file = real(joined);
    if (real_base.empty() || real_file.empty()) return joined;
    // Component-wise prefix: "/data/set" does not contain "/data/settings/x".
    const bool inside = real_file.size() > real_base.size() && real_file.compare(0, real_base.size(), real_base) == 0 &&
                        (real_base == "/" || real_file[real_base.size()] == '/');
    if (!inside)
        throw Error(ErrorKind::Format, printable(joined) + ": leads outside " + printable(base) + " (symbolic link)");
    return joined;
}

}  // namespace vkfuse::io

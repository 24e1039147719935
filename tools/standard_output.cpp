#include "standard_output.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "io/json_value.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {

std::string json_string(std::string_view text) { return json::quote(text); }

std::string json_number(double value) {
    if (!std::isfinite(value)) return "null";
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

int checked_stdout(int status) {
    // errno still tells why an earlier write failed, unless something since
    // changed it: then the message says only that one did.
    const bool failed_before = std::ferror(stdout) != 0;
    if (std::fflush(stdout) != 0 || failed_before)
        throw Error(ErrorKind::Io, std::string("stdout: write failed: ") +
                                       (errno != 0 ? std::strerror(errno) : "an earlier write failed"));
    return status;
}

void print_checked(const std::string& text) {
    const bool written = std::fwrite(text.data(), 1, text.size(), stdout) == text.size();
    const int err = errno;
    checked_stdout(0);
    if (!written) throw Error(ErrorKind::Io, std::string("stdout: write failed: ") + std::strerror(err));
}

}  // namespace vkfuse::cli

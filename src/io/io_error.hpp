// io/io_error.hpp - how the I/O code reports a failure: one line, path first.
#pragma once
#include <string>
#include <system_error>

#include "vkfuse/error.hpp"

namespace vkfuse::io {

[[noreturn]] inline void fail(ErrorKind kind, const std::string& path, const std::string& problem) {
    throw Error(kind, path + ": " + problem);
}

// The text of an errno value; std::error_code's message is thread-safe where strerror is not.
inline std::string system_message(int err) { return std::error_code(err, std::generic_category()).message(); }

}  // namespace vkfuse::io

// io/io_error.hpp - how the I/O code reports a failure: one line, path first.
#pragma once
#include <string>
#include <system_error>

#include "vkfuse/core/error.hpp"

namespace vkfuse::io {

// problem with control characters written as escapes (\n, \x01): it may quote
// bytes of the file (a .npy dtype), and the message must stay one line.
inline std::string printable(const std::string& problem) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (char ch : problem) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else if (c < 0x20 || c == 0x7f) out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
        else out += ch;
    }
    return out;
}

[[noreturn]] inline void fail(ErrorKind kind, const std::string& path, const std::string& problem) {
    throw Error(kind, path + ": " + printable(problem));
}

// The text of an errno value; std::error_code's message is thread-safe where strerror is not.
inline std::string system_message(int err) { return std::error_code(err, std::generic_category()).message(); }

}  // namespace vkfuse::io

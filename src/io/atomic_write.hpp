// io/atomic_write.hpp - write a whole file or nothing.
#pragma once
#include <cstdio>
#include <functional>
#include <string>

namespace vkfuse::io {

// Creates a temporary file beside path, lets write_body fill it, flushes it to
// disk and renames it over path. If write_body throws, or anything fails, the
// temporary is removed and the exception (Error(Io) for system failures,
// naming path) propagates: path is never left partially written.
void write_atomically(const std::string& path, const std::function<void(std::FILE*)>& write_body);

}  // namespace vkfuse::io

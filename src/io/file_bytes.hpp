// io/file_bytes.hpp - a whole file in memory, with errors that name it.
#pragma once
#include <string>
#include <vector>

namespace vkfuse::io {

// The contents of the regular file at path. Throws Error(Io) "path: cannot
// open: No such file or directory", "path: not a regular file", ...
std::vector<unsigned char> read_file_bytes(const std::string& path);

}  // namespace vkfuse::io

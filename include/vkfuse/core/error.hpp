// vkfuse/core/error.hpp - the one exception type vkfuse throws.
#pragma once
#include <stdexcept>
#include <string>

namespace vkfuse {

// What went wrong, coarse enough for a caller to branch on.
enum class ErrorKind {
    InvalidArgument,  // unknown name, impossible level count, wrong frame count ...
    Io,               // missing/unreadable/unwritable file
    Format,           // corrupt or unsupported file contents
    Shape,            // inputs whose shapes or channel counts disagree
    Numeric,          // NaN or Inf in an input
    Device,           // no Vulkan loader/device, device lost, out of device memory; a camera that fails
    Timeout,          // a sensor that sent nothing for longer than it was given
    Unplugged,        // a sensor that went away; the same serial may come back
};

// Every failure vkfuse reports is an Error whose what() is one line naming the
// input (file, option or object) and the problem, e.g. "a.png: not a PNG file".
class Error : public std::runtime_error {
public:
    Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
    ErrorKind kind() const noexcept { return kind_; }

private:
    ErrorKind kind_;
};

// The Device error for memory the device or its driver could not provide
// (VK_ERROR_OUT_OF_HOST_MEMORY, VK_ERROR_OUT_OF_DEVICE_MEMORY, or an
// allocation the driver reported made but could not back): catchable apart
// from other device failures, as std::bad_alloc is for the host's memory
// (the Python module raises MemoryError for both).
class OutOfMemory : public Error {
public:
    explicit OutOfMemory(const std::string& message) : Error(ErrorKind::Device, message) {}
};

}  // namespace vkfuse

// device_tensor.hpp - a plan's fused images in shareable device memory, for
// Python (vkfuse.DeviceTensor; device_tensor.cpp says how it is shared).
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "shared.hpp"
#include "vkfuse/vk/interop.hpp"

namespace vkfuse::python {

class DeviceTensor {
public:
    // float32 images of `shape` (C order) at the start of memory.
    DeviceTensor(std::shared_ptr<DeviceMemory> memory, std::vector<std::int64_t> shape);

    // Images of `shape` in memory another device or process can import.
    // Throws Error(Device) naming "on_device" where the device cannot export.
    static DeviceTensor exportable(Context& context, std::vector<std::int64_t> shape);
    // Another process's export_fd() (fd stays the caller's). Throws Error
    // for a shape that does not fit allocation_size or an fd Vulkan refuses.
    static DeviceTensor import_fd(Context& context, int fd, std::uint64_t allocation_size,
                                  std::vector<std::int64_t> shape);

    const std::vector<std::int64_t>& shape() const { return shape_; }
    BufferRange range() const { return memory_->range(); }
    std::size_t bytes() const;
    std::uint64_t allocation_size() const;
    int export_fd() const;
    py::capsule dlpack() const;
    py::array_t<float> numpy() const;

private:
    std::shared_ptr<DeviceMemory> memory_;
    std::vector<std::int64_t> shape_;
};

void def_device_tensor(py::module_& m);

}  // namespace vkfuse::python

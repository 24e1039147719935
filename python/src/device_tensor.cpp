// vkfuse.DeviceTensor: a plan's fused images left in device memory that can
// be shared (VK_KHR_external_memory_fd), reachable from Python as a DLPack
// tensor on kDLVulkan and as an opaque fd another device or process imports.
//
//   plan = vkfuse.Plan(240, 320, on_device=True)   # python/vkfuse/_plan.py
//   fused, scores = plan.run(frames)                  # a DeviceTensor: nothing read back
//   fused.__dlpack__()                                # kDLVulkan; data: the VkBuffer handle
//   fd = fused.export_fd()                            # cudaImportExternalMemory(OpaqueFd, size=fused.allocation_size)
//
// The tensor is the plan's output buffer: the plan's next run() overwrites
// it, and the plan (with its memory) lives as long as any tensor or capsule
// of it does. Plan::run has waited for the device, so what a consumer reads
// after run() returns is that cycle's result.
#include "device_tensor.hpp"

#include <dlpack/dlpack.h>
#include <pybind11/stl.h>

#include <cstring>
#include <sys/stat.h>
#include <unistd.h>

#include "arrays.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::python {

DeviceTensor::DeviceTensor(std::shared_ptr<DeviceMemory> memory, std::vector<std::int64_t> shape)
    : memory_(std::move(memory)), shape_(std::move(shape)) {}

std::size_t DeviceTensor::bytes() const {
    std::size_t n = sizeof(float);
    for (std::int64_t d : shape_) n *= std::size_t(d);
    return n;
}

DeviceTensor DeviceTensor::exportable(Context& context, std::vector<std::int64_t> shape) {
    if (!context.device().external_memory_fd)
        throw Error(ErrorKind::Device, "on_device: " + context.device().name +
                                           " cannot share memory (no VK_KHR_external_memory_fd)");
    DeviceTensor t(nullptr, std::move(shape));
    t.memory_ = std::make_shared<DeviceMemory>(DeviceMemory::allocate_exportable(context, t.bytes()));
    return t;
}

DeviceTensor DeviceTensor::import_fd(Context& context, int fd, std::uint64_t allocation_size,
                                     std::vector<std::int64_t> shape) {
    if (shape.empty() || shape.size() > 4)
        throw Error(ErrorKind::InvalidArgument, "shape: " + std::to_string(shape.size()) + " dimensions; expected 1 to 4");
    std::uint64_t bytes = sizeof(float);
    for (std::int64_t d : shape) {
        // Checked before multiplying: the product never overflows.
        if (d < 1 || std::uint64_t(d) > allocation_size / bytes)
            throw Error(ErrorKind::InvalidArgument, "shape: float32 images of this shape do not fit allocation_size " +
                                                        std::to_string(allocation_size));
        bytes *= std::uint64_t(d);
    }
    DeviceTensor t(nullptr, std::move(shape));
    // An opaque fd is the exporting driver's; what it is cannot be checked,
    // but a pipe, socket or directory is never one (a driver handed a pipe
    // may wait on it forever), nor a file shorter than the memory.
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw Error(ErrorKind::InvalidArgument, "fd " + std::to_string(fd) + ": not open");
    if (S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode) || S_ISDIR(st.st_mode))
        throw Error(ErrorKind::InvalidArgument, "fd " + std::to_string(fd) + ": a pipe, socket or directory, not exported memory");
    if (S_ISREG(st.st_mode) && std::uint64_t(st.st_size) < allocation_size)
        throw Error(ErrorKind::InvalidArgument, "fd " + std::to_string(fd) + ": " + std::to_string(st.st_size) +
                                                    " bytes, less than allocation_size " + std::to_string(allocation_size));
    // Vulkan takes the fd on success only: a duplicate is given, so the
    // caller's fd stays the caller's either way.
    const int mine = ::dup(fd);
    if (mine < 0) throw Error(ErrorKind::InvalidArgument, "fd " + std::to_string(fd) + ": not open");
    try {
        t.memory_ = std::make_shared<DeviceMemory>(DeviceMemory::import_fd(context, mine, allocation_size));
    } catch (...) {
        ::close(mine);
        throw;
    }
    return t;
}

py::array_t<float> DeviceTensor::numpy() const {
    const void* host = memory_->mapped();
    if (!host)
        throw Error(ErrorKind::Device, "numpy(): the memory is not host-visible on this device; import export_fd() "
                                       "where it is used, or run the plan without on_device");
    std::vector<py::ssize_t> shape(shape_.begin(), shape_.end());
    py::array_t<float> out(shape);
    std::memcpy(out.mutable_data(), host, bytes());
    return out;
}

namespace {

// What a capsule's DLManagedTensor keeps alive: the tensor (and so its memory).
struct Held {
    DeviceTensor tensor;
    std::vector<std::int64_t> shape;
    DLManagedTensor managed{};
};

void delete_held(DLManagedTensor* m) { delete static_cast<Held*>(m->manager_ctx); }

// A capsule still named "dltensor" was never consumed: its producer frees it.
void capsule_destructor(PyObject* capsule) {
    if (!PyCapsule_IsValid(capsule, "dltensor")) return;
    auto* m = static_cast<DLManagedTensor*>(PyCapsule_GetPointer(capsule, "dltensor"));
    if (m && m->deleter) m->deleter(m);
}

}  // namespace

py::capsule DeviceTensor::dlpack() const {
    auto* held = new Held{*this, shape_, {}};
    DLTensor& t = held->managed.dl_tensor;
    // For kDLVulkan, DLPack's data is opaque: here the VkBuffer handle, the
    // image starting byte_offset bytes into it (a consumer on the same
    // VkDevice binds it; any other imports export_fd()).
    const BufferRange range = this->range();
    t.data = reinterpret_cast<void*>(std::uintptr_t(range.buffer));
    t.byte_offset = range.offset;
    t.device = {kDLVulkan, 0};
    t.ndim = int(held->shape.size());
    t.dtype = {kDLFloat, 32, 1};
    t.shape = held->shape.data();
    t.strides = nullptr;  // C order
    held->managed.manager_ctx = held;
    held->managed.deleter = delete_held;
    return py::capsule(&held->managed, "dltensor", capsule_destructor);
}

int DeviceTensor::export_fd() const { return memory_->export_fd(); }
std::uint64_t DeviceTensor::allocation_size() const { return memory_->size(); }

void def_device_tensor(py::module_& m) {
    py::class_<DeviceTensor>(m, "DeviceTensor",
                             "Fused images in shareable device memory (Plan(on_device=True)): float32, C order.")
        .def_property_readonly("shape", [](const DeviceTensor& t) { return py::tuple(py::cast(t.shape())); })
        .def_property_readonly("allocation_size", &DeviceTensor::allocation_size,
                               "The memory's size, which an importer of export_fd() must be told.")
        .def("__dlpack__", [](const DeviceTensor& t, const py::object&) { return t.dlpack(); },
             py::arg("stream") = py::none(), "A DLPack capsule on kDLVulkan; data is the VkBuffer handle.")
        .def("__dlpack_device__", [](const DeviceTensor&) { return py::make_tuple(int(kDLVulkan), 0); })
        .def("export_fd", &DeviceTensor::export_fd,
             "A new opaque fd of the memory (VK_KHR_external_memory_fd), the caller's to close or import.")
        .def("numpy", &DeviceTensor::numpy, "A host copy, where the memory is host-visible.")
        .def_static(
            "import_fd",
            [](int fd, std::uint64_t allocation_size, const std::vector<std::int64_t>& shape) {
                Context* context = open_backend(Backend::Vulkan);
                return DeviceTensor::import_fd(*context, fd, allocation_size, shape);
            },
            py::arg("fd"), py::arg("allocation_size"), py::arg("shape"),
            "Another process's export_fd() as a DeviceTensor on this process's device (fd stays the caller's).");
}

}  // namespace vkfuse::python

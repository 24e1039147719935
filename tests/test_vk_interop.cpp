// vkfuse embedded in a caller's Vulkan work (vkfuse/vk/interop.hpp): a
// Context on the caller's device, plans reading and writing the caller's
// buffers, recorded into its command buffers or submitted against a timeline
// semaphore, and memory shared between two devices and with the host. Every
// fused image is checked bit for bit against an ordinary Plan of the same
// configuration (itself checked against the reference elsewhere), and the
// caller's validation layer must stay silent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "caller_vulkan.hpp"
#include "expect_error.hpp"
#include "test_support.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/vk/interop.hpp"

namespace vkfuse::test {
namespace {

constexpr int kH = 96, kW = 128, kC = 3, kK = 3, kS = 2;  // K = 3: channel-sum needs it

caller::Device& caller_device() {
    static caller::Device device(/*validation=*/true);
    return device;
}

Context& caller_context() {
    static Context context = make_context(caller_device().describe());
    return context;
}

class Interop : public VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        caller_context();
        messages_ = caller_device().validation_messages();
    }
    void TearDown() override {
        EXPECT_EQ(caller_device().validation_messages(), messages_) << "the caller's validation layer spoke";
        VulkanTest::TearDown();
    }

private:
    std::uint64_t messages_ = 0;
};

PlanConfig config_of(Method method, PixelType input) {
    PlanConfig c;
    c.fusion.method = method;
    c.height = kH;
    c.width = kW;
    c.channels = kC;
    c.frames = kK;
    c.sensors = kS;
    c.input = input;
    return c;
}

// S*K frames of the config's shape, as the bytes a device buffer holds.
std::vector<std::uint8_t> frame_bytes(const PlanConfig& c, std::uint32_t seed) {
    const std::size_t n = std::size_t(c.height) * c.width * c.channels;
    const std::size_t pixel = c.input == PixelType::U8 ? 1 : 4;
    std::vector<std::uint8_t> bytes(n * pixel * c.frames * c.sensors);
    for (int f = 0; f < c.frames * c.sensors; ++f) {
        const ImageD img = structured_image(c.height, c.width, c.channels, seed + std::uint32_t(f));
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t at = std::size_t(f) * n + i;
            if (pixel == 1) {
                bytes[at] = std::uint8_t(std::lround(std::clamp(img.data[i], 0.0, 1.0) * 255));
            } else {
                const float v = float(img.data[i]);
                std::memcpy(&bytes[at * 4], &v, 4);
            }
        }
    }
    return bytes;
}

std::vector<FrameView> views_of(const PlanConfig& c, const std::vector<std::uint8_t>& bytes) {
    std::vector<FrameView> views;
    const std::size_t frame = std::size_t(c.height) * c.width * c.channels * (c.input == PixelType::U8 ? 1 : 4);
    for (int f = 0; f < c.frames * c.sensors; ++f)
        views.push_back({bytes.data() + f * frame, c.height, c.width, c.channels, c.input});
    return views;
}

// An ordinary plan's results: what every embedded way must reproduce exactly.
struct Expected {
    std::vector<float> fused;  // S images, HWC
    std::vector<Metrics> metrics;
};

Expected ordinary(const PlanConfig& c, const std::vector<std::uint8_t>& bytes, Context& ctx = shared_context()) {
    Plan plan(ctx, c);
    plan.run(views_of(c, bytes));
    Expected e;
    for (int s = 0; s < c.sensors; ++s) {
        const Image& f = plan.fused(s);
        e.fused.insert(e.fused.end(), f.data.begin(), f.data.end());
        e.metrics.push_back(plan.metrics(s));
    }
    return e;
}

void expect_same(const Expected& e, const float* fused, const Plan& plan, const std::string& what) {
    EXPECT_EQ(std::memcmp(e.fused.data(), fused, e.fused.size() * 4), 0) << what << ": fused images differ";
    for (int s = 0; s < int(e.metrics.size()); ++s) {
        EXPECT_EQ(plan.metrics(s).sharpness, e.metrics[std::size_t(s)].sharpness) << what;
        EXPECT_EQ(plan.metrics(s).contrast, e.metrics[std::size_t(s)].contrast) << what;
    }
}

std::size_t fused_bytes(const PlanConfig& c) { return std::size_t(c.height) * c.width * c.channels * c.sensors * 4; }

TEST_F(Interop, TheCallersDeviceIsTheOneTheContextUses) {
    Context& ctx = caller_context();
    EXPECT_EQ(ctx.device().name, shared_context().device().name);
    EXPECT_EQ(ctx.filter_arithmetic(), shared_context().filter_arithmetic());
    EXPECT_EQ(ctx.device().external_memory_fd, caller_device().describe().external_memory_fd);
}

TEST_F(Interop, RecordedIntoTheCallersCommandBufferEveryMethodAndInput) {
    caller::Device& dev = caller_device();
    for (Method method : {Method::Wavelet, Method::Laplacian, Method::Brovey, Method::ChannelSum})
        for (PixelType input : {PixelType::U8, PixelType::F32}) {
            const PlanConfig c = config_of(method, input);
            const std::string what = std::string(to_string(method)) + (input == PixelType::U8 ? " u8" : " f32");
            const std::vector<std::uint8_t> bytes = frame_bytes(c, 11);
            caller::HostBuffer frames = dev.buffer(bytes.size()), fused = dev.buffer(fused_bytes(c));
            std::memcpy(frames.mapped, bytes.data(), bytes.size());
            std::memset(fused.mapped, 0xff, fused.size);
            Plan plan = make_plan(caller_context(), c, {frames.range(), fused.range()});
            VkCommandBuffer cmd = dev.begin();
            record(plan, cmd);
            dev.submit_and_wait(cmd);
            finished(plan);
            expect_same(ordinary(c, bytes), static_cast<const float*>(fused.mapped), plan, what);
            expect_error([&] { plan.fused(0); }, "plan", ErrorKind::InvalidArgument, "caller's buffer");
        }
}

TEST_F(Interop, RunReadsTheFramesWhereTheyLieOnTheDevice) {
    const PlanConfig c = config_of(Method::Wavelet, PixelType::U8);
    caller::Device& dev = caller_device();
    const std::vector<std::uint8_t> bytes = frame_bytes(c, 3);
    // An offset range: the frames start 256 bytes into the caller's buffer.
    caller::HostBuffer frames = dev.buffer(bytes.size() + 256);
    std::memcpy(static_cast<std::uint8_t*>(frames.mapped) + 256, bytes.data(), bytes.size());
    Plan plan = make_plan(caller_context(), c, {frames.range(256), {}});
    plan.run({});
    const Expected e = ordinary(c, bytes);
    std::vector<float> fused;
    for (int s = 0; s < kS; ++s) fused.insert(fused.end(), plan.fused(s).data.begin(), plan.fused(s).data.end());
    expect_same(e, fused.data(), plan, "run({})");
    const auto views = views_of(c, bytes);
    expect_error([&] { plan.run(views); }, "plan run", ErrorKind::InvalidArgument, "device buffer");
}

// Float32 frames read from the device are taken at their own scale, so the
// plan's backgrounds must reach the device at that scale too: the difference
// with background equals an ordinary plan's, which uploads both itself.
TEST_F(Interop, DeviceFloatFramesAreComparedWithTheirBackgrounds) {
    PlanConfig c = config_of(Method::Wavelet, PixelType::F32);
    c.metrics = {Metric::Sharpness, Metric::Contrast, Metric::BackgroundDiff};
    caller::Device& dev = caller_device();
    const std::vector<std::uint8_t> bytes = frame_bytes(c, 70);
    const std::vector<std::uint8_t> backgrounds = frame_bytes(c, 80);
    const std::vector<FrameView> background_views = views_of(c, backgrounds);
    caller::HostBuffer frames = dev.buffer(bytes.size());
    std::memcpy(frames.mapped, bytes.data(), bytes.size());
    Plan embedded = make_plan(caller_context(), c, {frames.range(), {}});
    Plan own(shared_context(), c);
    for (int s = 0; s < kS; ++s) {
        // Sensor s's background is the first frame of the seed-80 set for it.
        embedded.set_background(s, background_views[std::size_t(s * kK)]);
        own.set_background(s, background_views[std::size_t(s * kK)]);
    }
    for (int cycle = 0; cycle < 2; ++cycle) {  // the second cycle reuses what the first wrote
        embedded.run({});
        own.run(views_of(c, bytes));
        for (int s = 0; s < kS; ++s) {
            const Metrics got = embedded.metrics(s), want = own.metrics(s);
            ASSERT_TRUE(got.background_diff.has_value()) << "sensor " << s;
            ASSERT_TRUE(want.background_diff.has_value());
            EXPECT_GT(*want.background_diff, 0.01) << "the backgrounds differ from the frames";
            EXPECT_EQ(*got.background_diff, *want.background_diff) << "sensor " << s << " cycle " << cycle;
            EXPECT_EQ(got.sharpness, want.sharpness);
            EXPECT_EQ(got.contrast, want.contrast);
        }
    }
}

TEST_F(Interop, SubmitSignalsTheTimelineTheCallersWorkWaitsOn) {
    const PlanConfig c = config_of(Method::Laplacian, PixelType::F32);
    caller::Device& dev = caller_device();
    caller::HostBuffer fused = dev.buffer(fused_bytes(c)), copy = dev.buffer(fused_bytes(c));
    Plan plan = make_plan(caller_context(), c, {{}, fused.range()});
    for (std::uint32_t cycle = 0; cycle < 3; ++cycle) {
        const std::vector<std::uint8_t> bytes = frame_bytes(c, 20 + cycle);
        upload(plan, views_of(c, bytes));
        const std::uint64_t value = submit(plan);
        EXPECT_EQ(value, cycle + 1);
        // The caller's own submission starts once the plan's cycle ended.
        VkCommandBuffer cmd = dev.begin();
        const VkBufferCopy region{0, 0, fused_bytes(c)};
        vkCmdCopyBuffer(cmd, fused.buffer, copy.buffer, 1, &region);
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr,
                             0, nullptr);
        dev.submit_and_wait(cmd, timeline(plan), value);
        wait(plan);
        std::uint64_t reached = 0;
        ASSERT_EQ(vkGetSemaphoreCounterValue(dev.device(), timeline(plan), &reached), VK_SUCCESS);
        EXPECT_EQ(reached, value);
        expect_same(ordinary(c, bytes), static_cast<const float*>(copy.mapped), plan,
                    "cycle " + std::to_string(cycle));
    }
    EXPECT_EQ(plan.submits(), 3u);
}

// A timeline semaphore of the caller's that a submitted cycle waits for.
// Reached (and the plan waited for) when the test leaves, even early: a cycle
// still waiting would otherwise hold the plan's destructor forever.
class Gate {
public:
    Gate(VkDevice device, Plan& plan) : device_(device), plan_(plan) {
        VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
        type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        sci.pNext = &type;
        if (vkCreateSemaphore(device_, &sci, nullptr, &semaphore_) != VK_SUCCESS) throw std::runtime_error("semaphore");
    }
    ~Gate() {
        open();
        wait(plan_);
        vkDestroySemaphore(device_, semaphore_, nullptr);
    }
    VkSemaphore semaphore() const { return semaphore_; }
    void open() {
        std::uint64_t now = 0;
        vkGetSemaphoreCounterValue(device_, semaphore_, &now);
        if (now >= 1) return;
        VkSemaphoreSignalInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO};
        signal.semaphore = semaphore_;
        signal.value = 1;
        vkSignalSemaphore(device_, &signal);
    }

private:
    VkDevice device_;
    Plan& plan_;
    VkSemaphore semaphore_ = VK_NULL_HANDLE;
};

TEST_F(Interop, SubmitStartsOnlyOnceTheCallersSemaphoreIsReached) {
    const PlanConfig c = config_of(Method::Brovey, PixelType::U8);
    caller::Device& dev = caller_device();
    const std::vector<std::uint8_t> first = frame_bytes(c, 90), second = frame_bytes(c, 95);
    caller::HostBuffer frames = dev.buffer(first.size());
    std::memcpy(frames.mapped, first.data(), first.size());
    Plan plan = make_plan(caller_context(), c, {frames.range(), {}});
    plan.run({});
    std::memcpy(frames.mapped, second.data(), second.size());
    Gate gate(dev.device(), plan);
    const SemaphoreWait waits[] = {{gate.semaphore(), 1, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT}};
    const std::uint64_t value = submit(plan, waits);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::uint64_t reached = 0;
    ASSERT_EQ(vkGetSemaphoreCounterValue(dev.device(), timeline(plan), &reached), VK_SUCCESS);
    EXPECT_LT(reached, value) << "the cycle ran before the caller's semaphore was reached";
    // The first cycle's results are not handed out as the second's.
    expect_error([&] { plan.metrics(0); }, "plan", ErrorKind::InvalidArgument, "metrics() while a submitted cycle is pending");
    expect_error([&] { plan.fused(0); }, "plan", ErrorKind::InvalidArgument, "fused() while a submitted cycle is pending");
    gate.open();
    wait(plan);
    ASSERT_EQ(vkGetSemaphoreCounterValue(dev.device(), timeline(plan), &reached), VK_SUCCESS);
    EXPECT_EQ(reached, value);
    std::vector<float> fused;
    for (int s = 0; s < kS; ++s) fused.insert(fused.end(), plan.fused(s).data.begin(), plan.fused(s).data.end());
    expect_same(ordinary(c, second), fused.data(), plan, "after the gate");
}

TEST_F(Interop, BadBuffersAndCallsGetOneLine) {
    caller::Device& dev = caller_device();
    const PlanConfig c = config_of(Method::Wavelet, PixelType::U8);
    caller::HostBuffer big = dev.buffer(fused_bytes(c) + 256);
    expect_error([&] { make_plan(caller_context(), c, {big.range(8), {}}); }, "make_plan frames buffer",
                 ErrorKind::InvalidArgument, "offset 8 is not a multiple of");
    const BufferRange small{big.buffer, 0, 100};
    expect_error([&] { make_plan(caller_context(), c, {small, {}}); }, "make_plan frames buffer",
                 ErrorKind::InvalidArgument, "100 bytes, the plan needs");
    expect_error([&] { make_plan(caller_context(), c, {{}, small}); }, "make_plan fused buffer",
                 ErrorKind::InvalidArgument, "100 bytes");
    // A range past what the buffer holds would let the kernels read and
    // write beyond it; one merely larger than the plan needs is fine.
    const BufferRange claims_too_much{big.buffer, 0, VkDeviceSize(1) << 40};
    const std::size_t frames_needed = std::size_t(kH) * kW * kC * kK * kS;
    caller::HostBuffer short_buffer = dev.buffer(frames_needed / 2);
    const BufferRange past_the_end{short_buffer.buffer, 0, frames_needed};
    expect_error([&] { make_plan(caller_context(), c, {past_the_end, {}}); }, "make_plan frames buffer",
                 ErrorKind::InvalidArgument, "run past the buffer");
    const BufferRange offset_past{big.buffer, VkDeviceSize(1) << 40, frames_needed};
    expect_error([&] { make_plan(caller_context(), c, {offset_past, {}}); }, "make_plan frames buffer",
                 ErrorKind::InvalidArgument, "run past the buffer");
    EXPECT_NO_THROW(make_plan(caller_context(), c, {claims_too_much, {}})) << "only what the plan reads is bound";
    PlanConfig no_image = c;
    no_image.want_fused = false;
    expect_error([&] { make_plan(caller_context(), no_image, {{}, big.range()}); }, "make_plan",
                 ErrorKind::InvalidArgument, "without want_fused");
    PlanConfig skipping = c;
    skipping.skip.policy = SkipPolicy::Idle;
    expect_error([&] { make_plan(caller_context(), skipping); }, "make_plan", ErrorKind::InvalidArgument, "skip off");
    // Far-out float32 frames are scaled on the way to the device and their
    // result scaled back on the way out, which an image written into the
    // caller's buffer never takes: refused, not fused wrong.
    PlanConfig floats = config_of(Method::Wavelet, PixelType::F32);
    caller::HostBuffer fused = dev.buffer(fused_bytes(floats));
    Plan embedded = make_plan(caller_context(), floats, {{}, fused.range()});
    std::vector<std::uint8_t> huge = frame_bytes(floats, 5);
    for (std::size_t i = 0; i < huge.size(); i += 4) {
        float v;
        std::memcpy(&v, &huge[i], 4);
        v *= 1e20f;
        std::memcpy(&huge[i], &v, 4);
    }
    expect_error([&] { upload(embedded, views_of(floats, huge)); }, "sensor 0", ErrorKind::Numeric,
                 "caller's buffer");
    Plan own(caller_context(), c);
    VkCommandBuffer cmd = dev.begin();
    expect_error([&] { record(own, cmd); }, "record", ErrorKind::InvalidArgument, "not made by vkfuse::make_plan");
    dev.submit_and_wait(cmd);
    expect_error([&] { submit(own); }, "submit", ErrorKind::InvalidArgument, "not made by vkfuse::make_plan");
    CallerDevice none;
    expect_error([&] { make_context(none); }, "caller device", ErrorKind::InvalidArgument, "must all be given");
    CallerDevice wrong_family = dev.describe();
    wrong_family.queue_family = 99;
    expect_error([&] { make_context(wrong_family); }, "caller device", ErrorKind::InvalidArgument, "queue family 99");
    CallerDevice wrong_index = dev.describe();
    wrong_index.queue_index = 7;
    expect_error([&] { make_context(wrong_index); }, "caller device", ErrorKind::InvalidArgument, "queue index 7");
}

// Writes memory of the caller's device A where the host sees it (lavapipe),
// else through a host buffer and a copy on A's queue: a discrete GPU's
// exportable memory is device-local.
void write_on_a(const DeviceMemory& memory, const void* data, std::size_t bytes) {
    if (memory.mapped()) {
        std::memcpy(memory.mapped(), data, bytes);
        return;
    }
    caller::Device& dev = caller_device();
    caller::HostBuffer stage = dev.buffer(bytes);
    std::memcpy(stage.mapped, data, bytes);
    VkCommandBuffer cmd = dev.begin();
    const VkBufferCopy region{0, memory.range().offset, bytes};
    vkCmdCopyBuffer(cmd, stage.buffer, memory.range().buffer, 1, &region);
    dev.submit_and_wait(cmd);
}

// The floats in memory of device A, read likewise.
std::vector<float> read_on_a(const DeviceMemory& memory, std::size_t bytes) {
    std::vector<float> out(bytes / sizeof(float));
    if (memory.mapped()) {
        std::memcpy(out.data(), memory.mapped(), bytes);
        return out;
    }
    caller::Device& dev = caller_device();
    caller::HostBuffer stage = dev.buffer(bytes);
    VkCommandBuffer cmd = dev.begin();
    const VkBufferCopy region{memory.range().offset, 0, bytes};
    vkCmdCopyBuffer(cmd, memory.range().buffer, stage.buffer, 1, &region);
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr,
                         0, nullptr);
    dev.submit_and_wait(cmd);
    std::memcpy(out.data(), stage.mapped, bytes);
    return out;
}

// Device A is the caller's (caller_vulkan.hpp), device B vkfuse's own
// (shared_context(): another instance and VkDevice). A's frames reach B
// through an opaque fd; B's fused image comes back to A the same way.
TEST_F(Interop, FramesFromAnotherDeviceAndTheFusedImageBack) {
    Context& a = caller_context();
    Context& b = shared_context();
    if (!a.device().external_memory_fd || !b.device().external_memory_fd)
        GTEST_SKIP() << a.device().name << " has no VK_KHR_external_memory_fd";
    const PlanConfig c = config_of(Method::Wavelet, PixelType::U8);
    const std::vector<std::uint8_t> bytes = frame_bytes(c, 40);
    DeviceMemory frames_a = DeviceMemory::allocate_exportable(a, bytes.size());
    write_on_a(frames_a, bytes.data(), bytes.size());
    DeviceMemory frames_b = DeviceMemory::import_fd(b, frames_a.export_fd(), frames_a.size());
    DeviceMemory fused_b = DeviceMemory::allocate_exportable(b, fused_bytes(c));
    Plan plan = make_plan(b, c, {frames_b.range(), fused_b.range()});
    plan.run({});
    DeviceMemory fused_a = DeviceMemory::import_fd(a, fused_b.export_fd(), fused_b.size());
    expect_same(ordinary(c, bytes), read_on_a(fused_a, fused_bytes(c)).data(), plan, "through two fds");
    expect_error([&] { (void)frames_b.export_fd(); }, "export_fd", ErrorKind::InvalidArgument, "allocate_exportable");
    expect_error([&] { DeviceMemory::import_fd(b, -1, 4096); }, "import_fd", ErrorKind::InvalidArgument, "not open");
}

struct FreeAligned {
    void operator()(void* p) const { std::free(p); }
};

TEST_F(Interop, HostMemoryIsReadInPlaceOrStagedWhereItIsSystemMemory) {
    Context& ctx = shared_context();
    const VkDeviceSize align = DeviceMemory::host_pointer_alignment(ctx);
    if (!ctx.device().external_memory_host) GTEST_SKIP() << ctx.device().name << " has no VK_EXT_external_memory_host";
    const PlanConfig c = config_of(Method::Laplacian, PixelType::U8);
    const std::vector<std::uint8_t> first = frame_bytes(c, 50), second = frame_bytes(c, 60);
    const std::size_t bytes = (first.size() + align - 1) / align * align;
    std::unique_ptr<void, FreeAligned> host(std::aligned_alloc(align, bytes));
    std::memcpy(host.get(), first.data(), first.size());
    DeviceMemory imported = DeviceMemory::import_host(ctx, host.get(), bytes);
    EXPECT_EQ(imported.mapped(), host.get());
    Plan plan = make_plan(ctx, c, {imported.range(), {}});
    for (const auto* frames : {&first, &second}) {
        // The host writes its memory; the next run sees it, with no upload.
        std::memcpy(host.get(), frames->data(), frames->size());
        plan.run({});
        std::vector<float> fused;
        for (int s = 0; s < kS; ++s) fused.insert(fused.end(), plan.fused(s).data.begin(), plan.fused(s).data.end());
        expect_same(ordinary(c, *frames), fused.data(), plan, "host memory");
    }
    expect_error([&] { DeviceMemory::import_host(ctx, static_cast<std::uint8_t*>(host.get()) + 1, align); },
                 "import_host", ErrorKind::InvalidArgument, "multiples of " + std::to_string(align));
    // Read in place where the import is device memory (lavapipe's own types);
    // on a discrete GPU, or under the discrete profile
    // (tools/vulkan_variants.sh), it is system memory, copied in at the start
    // of each cycle instead.
    bool copied = false;
    for (const std::string& what : ctx.adaptations()) copied = copied || what.find("imported host memory") != std::string::npos;
    EXPECT_EQ(copied, ctx.device().type == "discrete" || ctx.device_profile() == "discrete-no-rebar");
}

// On a discrete GPU imported host memory is system memory: a plan reading its
// frames there copies them into device-local memory at the start of each
// cycle, rather than have every kernel read them across the bus.
TEST_F(Interop, HostMemoryOnADiscreteGpuIsCopiedIntoDeviceMemoryEachCycle) {
    if (!shared_context().device().external_memory_host) GTEST_SKIP() << "no VK_EXT_external_memory_host";
    ContextOptions o = validated_options();
    o.device_profile = "discrete-no-rebar";
    Context ctx(o);
    const VkDeviceSize align = DeviceMemory::host_pointer_alignment(ctx);
    const PlanConfig c = config_of(Method::Wavelet, PixelType::U8);
    const std::vector<std::uint8_t> first = frame_bytes(c, 80), second = frame_bytes(c, 90);
    const std::size_t bytes = (first.size() + align - 1) / align * align;
    std::unique_ptr<void, FreeAligned> host(std::aligned_alloc(align, bytes));
    DeviceMemory imported = DeviceMemory::import_host(ctx, host.get(), bytes);
    Plan plan = make_plan(ctx, c, {imported.range(), {}});
    bool said = false;
    for (const std::string& what : ctx.adaptations())
        said = said || what == "frames in imported host memory are copied into device-local memory before each cycle";
    EXPECT_TRUE(said);
    for (const auto* frames : {&first, &second}) {
        std::memcpy(host.get(), frames->data(), frames->size());
        plan.run({});
        std::vector<float> fused;
        for (int s = 0; s < kS; ++s) fused.insert(fused.end(), plan.fused(s).data.begin(), plan.fused(s).data.end());
        expect_same(ordinary(c, *frames, ctx), fused.data(), plan, "staged host memory");
    }
    EXPECT_EQ(ctx.validation_message_count(), 0u);
}

}  // namespace
}  // namespace vkfuse::test

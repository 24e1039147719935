// One validated Vulkan context per test binary; every GPU test asserts that
// the validation layer stayed silent while it ran.
#pragma once
#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

#include "vkfuse/vk/context.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::test {

struct ValidationLog {
    std::mutex mutex;
    std::vector<std::string> messages;
};

ValidationLog& validation_log();
Context& shared_context();  // created on first use with validation on
// Validation on, every message into validation_log(): what shared_context uses.
// Where the layer is not installed (a GPU machine without
// vulkan-validationlayers) the tests run without it, saying so once on stderr,
// and the tests of validation itself skip.
ContextOptions validated_options();
bool validation_available();
#define SKIP_WITHOUT_VALIDATION() \
    if (!::vkfuse::test::validation_available()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed"
// A validated context per filter arithmetic the device has: shared_context()
// first, then, where the device also offers the other one, a context using it
// (created on first use), so the path a GPU takes is tested on lavapipe too.
std::vector<Context*> filter_arithmetic_contexts();
// A validated context per filter arithmetic the device has, and one more for
// compensated float32 with products split (Dekker's, what a device whose fma
// is not fused runs): "float64", "compensated float32", "... split products".
std::string arithmetic_name(const Context& context);
// A validated context whose plans all reach their buffers through device
// addresses (ContextOptions::device_addresses_only), created on first use.
// Only where the device has them (a profile may take them away):
// SKIP_WITHOUT_DEVICE_ADDRESSES() first.
Context& addressed_context();
// A validated context whose kernels reach their buffers through descriptor
// bindings (KernelBuffers::Bound, every GPU's way), whatever the device's
// default, created on first use.
Context& bound_context();
bool has_device_addresses();
#define SKIP_WITHOUT_DEVICE_ADDRESSES() \
    if (!::vkfuse::test::has_device_addresses()) GTEST_SKIP() << "the device (or its profile) has no device addresses"
// Differently compiled kernels (bound and addressed variants, one block and
// several) may contract multiply-adds differently on a GPU: equal bits on CPU
// devices (lavapipe), within kModuleUlps of each other elsewhere.
inline constexpr double kModuleUlps = 8;
double module_ulps(const Context& context);  // 0 on a CPU device, else kModuleUlps

class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    Context& ctx() { return shared_context(); }

private:
    std::size_t messages_before_ = 0;
};

// Runs one plan over frames (sensor-major, S*K images) and returns it.
Plan run_plan(Context& ctx, const PlanConfig& cfg, const std::vector<Image>& frames);

}  // namespace vkfuse::test

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
ContextOptions validated_options();
// A validated context per filter arithmetic the device has: shared_context()
// first, then, where the device also offers the other one, a context using it
// (created on first use), so the path a GPU takes is tested on lavapipe too.
std::vector<Context*> filter_arithmetic_contexts();
// A validated context whose plans all reach their buffers through device
// addresses (ContextOptions::device_addresses_only), created on first use.
Context& addressed_context();

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

// The device probes behind vkfuse-bench's "kernel access" lines: each runs
// under the validation layer, checks every float it wrote against the host
// (a probe that computes the wrong thing throws instead of reporting a
// speed), and reports finite, positive costs.
#include <gtest/gtest.h>

#include <cmath>

#include "expect_error.hpp"
#include "vk/probes/kernel_access.hpp"
#include "vk_fixture.hpp"

namespace vkfuse::test {
namespace {

class KernelAccessTest : public VulkanTest {};

bool positive(double v) { return std::isfinite(v) && v > 0; }

TEST_F(KernelAccessTest, EveryProbeRunsAndChecksItsOutput) {
    const vk::KernelAccess a = vk::measure_kernel_access(ctx(), std::uint64_t(1) << 20, 1);
    EXPECT_EQ(a.floats, 262144u);
    EXPECT_EQ(a.device_addresses, ctx().device().device_addresses);
    if (a.device_addresses) {  // the address probes need them (a profile may take them away)
        EXPECT_TRUE(positive(a.address_ns)) << a.address_ns;
        EXPECT_TRUE(positive(a.address_vec4_ns)) << a.address_vec4_ns;
    } else {
        EXPECT_EQ(a.address_ns, 0);
    }
    EXPECT_TRUE(positive(a.bound_ns)) << a.bound_ns;
    EXPECT_TRUE(positive(a.bound_vec4_ns)) << a.bound_vec4_ns;
    EXPECT_TRUE(positive(a.shared_exchange_ns)) << a.shared_exchange_ns;
    EXPECT_TRUE(positive(a.fma_gflops)) << a.fma_gflops;
    EXPECT_TRUE(positive(a.dispatch_us)) << a.dispatch_us;
}

TEST_F(KernelAccessTest, SizesThatAreNotWholeGroupsAreRoundedDown) {
    // 5000 bytes = 1250 floats: one whole group of 256 vec4 (1024 floats) fits.
    EXPECT_EQ(vk::measure_kernel_access(ctx(), 5000, 1).floats, 1024u);
}

TEST_F(KernelAccessTest, RejectsTooFewBytesOrRepeats) {
    expect_error([&] { vk::measure_kernel_access(ctx(), 4095, 1); }, "kernel access probe", ErrorKind::InvalidArgument,
                 "bytes must be >= 4096");
    expect_error([&] { vk::measure_kernel_access(ctx(), 4096, 0); }, "kernel access probe", ErrorKind::InvalidArgument,
                 "repeats");
}

}  // namespace
}  // namespace vkfuse::test

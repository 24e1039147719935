// Real and virtual clocks.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "vkfuse/sensor/clock.hpp"

namespace vkfuse {
namespace {

TEST(VirtualClock, StartsAtZeroAndJumpsForwardOnly) {
    auto clock = make_virtual_clock();
    EXPECT_EQ(clock->now(), 0.0);
    clock->wait_until(2.5);
    EXPECT_EQ(clock->now(), 2.5);
    clock->wait_until(1.0);  // the past: nothing happens
    EXPECT_EQ(clock->now(), 2.5);
}

TEST(VirtualClock, WaitingTakesNoRealTime) {
    auto clock = make_virtual_clock();
    const auto start = std::chrono::steady_clock::now();
    clock->wait_until(3600.0);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
    EXPECT_EQ(clock->now(), 3600.0);
}

TEST(VirtualClock, ThreadsSharingItEndAtTheLatestTime) {
    auto clock = make_virtual_clock();
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&clock, t] {
            for (int i = 0; i < 1000; ++i) {
                const double before = clock->now();
                clock->wait_until(t * 1000 + i);
                EXPECT_GE(clock->now(), before);  // never backwards, whoever else waits
            }
        });
    for (auto& th : threads) th.join();
    EXPECT_EQ(clock->now(), 3999.0);
}

TEST(RealClock, FollowsSteadyTimeAndSleeps) {
    auto clock = make_real_clock();
    const double t0 = clock->now();
    EXPECT_GE(t0, 0.0);
    EXPECT_LT(t0, 1.0);
    clock->wait_until(t0 + 0.02);
    EXPECT_GE(clock->now(), t0 + 0.02);
    EXPECT_LT(clock->now(), t0 + 2.0);
}

}  // namespace
}  // namespace vkfuse

// The per-coefficient fusion rules (docs/spec.md, "Rules").
#include <gtest/gtest.h>

#include <vector>

#include "core/rules.hpp"

namespace vkfuse {
namespace {

TEST(CpuRules, MaxAbsPicksLargestMagnitudeKeepingSign) {
    const std::vector<double> v{0.2, -0.7, 0.5};
    EXPECT_EQ(core::combine(Rule::MaxAbs, v), -0.7);
}

TEST(CpuRules, MaxAbsTiesGoToTheLowestFrame) {
    EXPECT_EQ(core::combine(Rule::MaxAbs, std::vector<double>{0.1, -0.5, 0.5}), -0.5);
    EXPECT_EQ(core::combine(Rule::MaxAbs, std::vector<double>{0.5, -0.5}), 0.5);
    EXPECT_EQ(core::combine(Rule::MaxAbs, std::vector<double>{0.0, -0.0}), 0.0);
}

TEST(CpuRules, MeanMaxMin) {
    const std::vector<double> v{0.25, -1.0, 2.0, 0.75};
    EXPECT_DOUBLE_EQ(core::combine(Rule::Mean, v), 0.5);
    EXPECT_EQ(core::combine(Rule::Max, v), 2.0);
    EXPECT_EQ(core::combine(Rule::Min, v), -1.0);
    EXPECT_EQ(core::combine(Rule::Mean, std::vector<double>{0.3}), 0.3);
}

TEST(CpuRules, PlanesAreCombinedPositionByPosition) {
    core::Plane a(1, 3), b(1, 3);
    a.data = {1, -4, 0};
    b.data = {-2, 3, 0};
    const std::vector<const core::Plane*> planes{&a, &b};
    EXPECT_EQ(core::combine_planes(Rule::MaxAbs, planes).data, (std::vector<double>{-2, -4, 0}));
    EXPECT_EQ(core::combine_planes(Rule::Max, planes).data, (std::vector<double>{1, 3, 0}));
}

}  // namespace
}  // namespace vkfuse

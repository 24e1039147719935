// Every fusion method has its row in both method tables: core/method_table.hpp
// (names, limits, reference) and vk/plan/method_recorders.hpp (how a plan records
// it). A Method without a row does not compile (both lookups switch over every
// enumerator with no default); these tests check what the compiler cannot:
// that the rows agree with their enumerators and cover the enum.
#include <gtest/gtest.h>

#include <string>

#include "core/method_table.hpp"
#include "vk/plan/method_recorders.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::test {
namespace {

TEST(MethodTables, EveryMethodHasBothRowsInEnumOrder) {
    const auto rows = core::method_table();
    ASSERT_FALSE(rows.empty());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const core::MethodInfo& row = rows[i];
        SCOPED_TRACE(std::string(row.name));
        EXPECT_EQ(int(row.method), int(i));
        EXPECT_EQ(&core::method_info(row.method), &row);
        EXPECT_EQ(vk::method_recorder(row.method).method, row.method);
        EXPECT_EQ(parse_method(row.name), row.method);
        EXPECT_EQ(to_string(row.method), row.name);
        EXPECT_NE(row.reference, nullptr);
        EXPECT_NE(vk::method_recorder(row.method).record, nullptr);
        EXPECT_FALSE(row.summary.empty());
        EXPECT_FALSE(row.plot_colour.empty());
    }
    // Past the last row there is no enumerator: both lookups refuse it.
    const Method past = Method(int(rows.size()));
    EXPECT_THROW(core::method_info(past), Error);
    EXPECT_THROW(vk::method_recorder(past), Error);
}

TEST(MethodTables, HelpListsEveryMethod) {
    const std::string names = core::method_names();
    for (const core::MethodInfo& row : core::method_table())
        EXPECT_NE(names.find(std::string(row.name)), std::string::npos) << names;
}

}  // namespace
}  // namespace vkfuse::test

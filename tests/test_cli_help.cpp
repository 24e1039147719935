// --help, --version and info: exit 0, on stdout, saying what the user needs.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "core/method_table.hpp"

namespace vkfuse::test {
namespace {

void expect_help(const std::vector<std::string>& args, const std::vector<std::string>& mentions) {
    CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("Usage: vkfuse"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Example:\n  vkfuse "), std::string::npos) << r.out;
    for (const std::string& m : mentions) EXPECT_NE(r.out.find(m), std::string::npos) << m << " in\n" << r.out;
}

TEST(CliHelp, TopLevelListsTheCommands) {
    for (std::string flag : {"--help", "-h"}) expect_help({flag}, {"fuse ", "metrics ", "info ", "--version"});
}

TEST(CliHelp, FuseListsEveryOptionWithItsDefault) {
    expect_help({"fuse", "--help"},
                {"--method M", "--levels L", "laplacian 4, wavelet 3", "--wavelet W", "default bior4.4", "--mode MODE",
                 "default periodization", "--base-rule R", "default mean", "--detail-rule R", "default max-abs",
                 "--backend B", "default auto", "-o, --output OUT", "-h, --help"});
}

// Every command that takes --method says what each method does, from its row.
TEST(CliHelp, MethodsSectionHasEveryRowsSummary) {
    for (const char* command : {"fuse", "run"}) {
        std::vector<std::string> mentions{"\nMethods:\n"};
        for (const core::MethodInfo& m : core::method_table())
            mentions.push_back("  " + std::string(m.name) + " ");
        for (const core::MethodInfo& m : core::method_table()) mentions.push_back(std::string(m.summary) + "\n");
        expect_help({command, "--help"}, mentions);
    }
    CliResult metrics = run_cli({"metrics", "--help"});
    EXPECT_EQ(metrics.out.find("Methods:"), std::string::npos) << metrics.out;
}

TEST(CliHelp, MetricsAndInfo) {
    expect_help({"metrics", "-h"}, {"--background BG", "--backend B", "\"background_diff\""});
    expect_help({"info", "--help"}, {"Vulkan"});
}

TEST(CliHelp, HelpWinsOverOtherArguments) {
    expect_help({"fuse", "--bogus", "x", "--help"}, {"--method M"});
}

TEST(CliHelp, Version) {
    CliResult r = run_cli({"--version"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out.rfind("vkfuse ", 0), 0u) << r.out;
    EXPECT_EQ(r.out.back(), '\n');
}

// With or without a Vulkan loader and device, info succeeds and says what auto does.
TEST(CliInfo, SaysWhatAutoUses) {
    CliResult r = run_cli({"info"});
    EXPECT_EQ(r.status, 0) << r.err;
    bool devices = r.out.find("Vulkan devices:\n  [0] ") != std::string::npos &&
                   r.out.find("--backend auto uses ") != std::string::npos;
    bool none = r.out.find("the CPU reference path will be used") != std::string::npos;
    EXPECT_TRUE(devices || none) << r.out;
}

}  // namespace
}  // namespace vkfuse::test

// vkfuse run --metrics: a run computes and writes only the metrics it was
// asked for, with the values a run of all three gives.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace vkfuse::test {
namespace {

// The text of key's value in a metrics line ("" when the line has no key):
// compared as text, since both runs print the same double the same way.
std::string value_of(const std::string& line, const std::string& key) {
    const std::string tag = "\"" + key + "\": ";
    const std::size_t at = line.find(tag);
    if (at == std::string::npos) return "";
    const std::size_t from = at + tag.size();
    return line.substr(from, line.find_first_of(",}", from) - from);
}

std::vector<std::string> metric_lines(const std::string& backend, const std::vector<std::string>& extra,
                                      TempDir& tmp, const std::string& name) {
    std::vector<std::string> args{"run", "--virtual-clock", "--cycles", "4", "--background-frames", "2",
                                  "--motion", "tap", "--motion-period", "0.2", "--backend", backend,
                                  "--out", tmp.file(name)};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 0) << r.err;
    return lines_of(read_bytes(tmp.file(name + "/metrics.jsonl")));
}

TEST(CliRunMetrics, OnlyTheMetricsAskedForAreWrittenWithTheirFullValues) {
    const std::vector<std::string> keys{"sharpness", "contrast", "background_diff"};
    for (const std::string backend : {"cpu", "vulkan"}) {
        SCOPED_TRACE(backend);
        TempDir tmp;
        const std::vector<std::string> all = metric_lines(backend, {}, tmp, "all");
        ASSERT_EQ(all.size(), 4u);
        for (const std::string list : {"contrast", "sharpness,background_diff", "background_diff,contrast"}) {
            SCOPED_TRACE(list);
            const std::vector<std::string> some = metric_lines(backend, {"--metrics", list}, tmp, list);
            ASSERT_EQ(some.size(), all.size());
            for (std::size_t i = 0; i < all.size(); ++i)
                for (const std::string& key : keys) {
                    const bool asked = list.find(key) != std::string::npos;
                    ASSERT_FALSE(value_of(all[i], key).empty()) << all[i];
                    EXPECT_EQ(value_of(some[i], key), asked ? value_of(all[i], key) : "") << some[i];
                }
        }
    }
}

TEST(CliRunMetrics, BadListsAreRefused) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--metrics", "sharpness,blur"},
         "--metrics sharpness,blur: expected a comma-separated list of sharpness,contrast,background_diff"},
        {{"--metrics", ""}, "--metrics : expected a comma-separated list of sharpness,contrast,background_diff"},
        {{"--metrics", "contrast,contrast"},
         "--metrics contrast,contrast: expected a comma-separated list of sharpness,contrast,background_diff"},
        {{"--metrics", "background_diff", "--background-frames", "0"},
         "--metrics background_diff: background_diff needs a background (--background-frames of at least 1)"},
    };
    for (const auto& [extra, message] : cases) expect_run_refused(extra, message);
}

}  // namespace
}  // namespace vkfuse::test

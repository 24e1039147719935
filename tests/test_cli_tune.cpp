// vkfuse tune: a configuration from a dataset or from the simulated DIGIT
// captured now, and vkfuse run --config taking it (the command line still
// winning); malformed configurations get one line.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "json_member.hpp"
#include "study_dataset.hpp"

namespace vkfuse::test {
namespace {

// The sequence a recorded run says it cycled through.
std::string recorded_sequence(const std::string& dir) {
    const Dataset d = read_dataset(dir);
    return d.run ? to_string(d.run->sequence) : "";
}

TEST(CliTune, ADatasetsWinnerRunsAsAConfig) {
    TempDir tmp;
    const std::string set = tmp.file("set"), config = tmp.file("tuned.json");
    write_study_dataset(set);
    const CliResult tune = run_cli({"tune", "--dataset", set, "--max-k", "2", "--out", config});
    ASSERT_EQ(tune.status, 0) << tune.err;
    const json::Value c = json::parse(read_bytes(config), config);
    EXPECT_EQ(member(c, "format").string(), "vkfuse-config");
    const std::string sequence = member(c, "sequence").string();
    EXPECT_EQ(parse_sequence(sequence).size(), 2u) << sequence;
    EXPECT_NO_THROW(parse_method(member(c, "method").string()));
    EXPECT_EQ(member(member(c, "tuned"), "source").string(), set);
    EXPECT_NE(tune.out.find(config + ": " + sequence + " fused by "), std::string::npos) << tune.out;
    // --methods: the winner is one of them.
    const std::string brovey = tmp.file("brovey.json");
    const CliResult only = run_cli({"tune", "--dataset", set, "--max-k", "2", "--methods", "brovey", "--out", brovey});
    ASSERT_EQ(only.status, 0) << only.err;
    EXPECT_EQ(member(json::parse(read_bytes(brovey), brovey), "method").string(), "brovey");

    const CliResult run = run_cli({"run", "--config", config, "--cycles", "2", "--virtual-clock", "--background-frames",
                                   "2", "--record", tmp.file("rec")});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("\"fused\": 2"), std::string::npos) << run.out;
    EXPECT_EQ(recorded_sequence(tmp.file("rec")), sequence);
    // What the command line says wins over the configuration.
    const CliResult mine = run_cli({"run", "--config", config, "--sequence", "15,15,15+0,15,0", "--cycles", "1",
                                    "--virtual-clock", "--background-frames", "2", "--record", tmp.file("rec2")});
    ASSERT_EQ(mine.status, 0) << mine.err;
    EXPECT_EQ(recorded_sequence(tmp.file("rec2")), "15,15,15+0,15,0");
}

TEST(CliTune, CapturesFromTheSimulatedDigit) {
    TempDir tmp;
    const std::string config = tmp.file("sim.json");
    const std::string kept = tmp.file("kept");
    const CliResult tune = run_cli({"tune", "--simulate", "--objects", "coin", "--grid", "0,15", "--max-k", "2",
                                    "--background-frames", "1", "--keep", kept, "--out", config});
    ASSERT_EQ(tune.status, 0) << tune.err;
    EXPECT_NE(tune.err.find("capturing from the simulated DIGIT"), std::string::npos) << tune.err;
    const json::Value c = json::parse(read_bytes(config), config);
    EXPECT_EQ(member(member(c, "tuned"), "source").string(), kept);
    // The frames kept are a dataset the study takes, and it agrees.
    const Dataset d = read_dataset(kept);
    ASSERT_EQ(d.sensors.size(), 1u);
    EXPECT_EQ(d.objects(), std::vector<std::string>{"coin"});
    const CliResult study = run_cli({"study", kept, "--max-k", "2", "--out", tmp.file("study")});
    ASSERT_EQ(study.status, 0) << study.err;
    const json::Value results = json::parse(read_bytes(tmp.file("study/results.json")), "results.json");
    EXPECT_EQ(member(member(results, "best"), "method").string(), member(member(c, "tuned"), "method").string());
    const CliResult run = run_cli({"run", "--config", config, "--cycles", "1", "--virtual-clock"});
    EXPECT_EQ(run.status, 0) << run.err;
}

TEST(CliTune, MalformedConfigsGetOneLine) {
    TempDir tmp;
    const auto refused = [&](const std::string& body, const std::string& fragment) {
        const std::string path = tmp.file("c.json");
        write_bytes(path, body);
        const CliResult r = run_cli({"run", "--config", path, "--cycles", "1", "--virtual-clock"});
        EXPECT_EQ(r.status, 2) << body;
        ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
        EXPECT_EQ(r.err.rfind("vkfuse: --config " + path, 0), 0u) << r.err;
        EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    };
    refused("{", "line");
    refused("[1]", "not a JSON object");
    refused(R"({"format": "other", "version": 1, "sequence": "15,15,15"})", "\"format\"");
    refused(R"({"format": "vkfuse-config", "version": 2, "sequence": "15,15,15"})", "version");
    refused(R"({"format": "vkfuse-config", "version": 1})", "no \"sequence\"");
    refused(R"({"format": "vkfuse-config", "version": 1, "sequence": "15,15,99"})", "99");
    refused(R"({"format": "vkfuse-config", "version": 1, "sequence": "15,15,15", "method": "magic"})", "magic");
    refused(R"({"format": "vkfuse-config", "version": 1, "sequence": "15,15,15", "levels": -1})", "levels");
    refused(R"({"format": "vkfuse-config", "version": 1, "sequence": 7})", "must be a string");
    const CliResult missing = run_cli({"run", "--config", tmp.file("none.json"), "--cycles", "1"});
    EXPECT_EQ(missing.status, 2);
    EXPECT_NE(missing.err.find("--config " + tmp.file("none.json")), std::string::npos) << missing.err;
}

// What would fail after the operator pressed every object fails before.
TEST(CliTune, RefusesBeforeCapturingWhatCouldNotBeStudied) {
    TempDir tmp;
    const auto refused = [&](std::vector<std::string> argv, const std::string& fragment) {
        const CliResult r = run_cli(argv);
        EXPECT_EQ(r.status, 2) << r.out;
        ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
        EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("capturing"), std::string::npos) << "captured first: " << r.err;
    };
    refused({"tune", "--simulate", "--grid", "0,5", "--out", tmp.file("a.json")}, "no static setting");
    refused({"tune", "--simulate", "--grid", "15", "--out", tmp.file("a.json")}, "one setting");
    refused({"tune", "--simulate", "--max-k", "1", "--out", tmp.file("a.json")}, "--max-k 1");
    refused({"tune", "--simulate", "--out", tmp.file("missing/a.json")}, "cannot write in");
    refused({"tune", "--simulate", "--objects", "../x", "--out", tmp.file("a.json")}, "--objects");
    refused({"tune", "--simulate", "--methods", "pca", "--out", tmp.file("a.json")}, "--methods: \"pca\"");
}

}  // namespace
}  // namespace vkfuse::test

// vkfuse tune: a configuration from a dataset or from the simulated DIGIT
// captured now, and vkfuse run --config taking it (the command line still
// winning); malformed configurations get one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cli_runner.hpp"
#include "json_member.hpp"
#include "run/run_config.hpp"
#include "vkfuse/core/io.hpp"
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

// Every field a configuration holds survives writing and reading, and `run
// --config` fuses with exactly those rules: base and detail rules that differ,
// so that swapping them (or dropping either) shows.
TEST(CliTune, AConfigRoundTripsEveryFieldAndRunFusesWithItsRules) {
    TempDir tmp;
    cli::RunConfig written;
    written.sequence = parse_sequence("15,15,15+0,15,0+5,5,5");
    written.fusion.method = Method::Wavelet;
    written.fusion.wavelet = Wavelet::Db2;
    written.fusion.levels = 2;
    written.fusion.mode = WaveletMode::Symmetric;
    written.fusion.base_rule = Rule::Max;
    written.fusion.detail_rule = Rule::Min;
    const std::string config = tmp.file("c.json");
    write_bytes(config, cli::run_config_json(written, json::Value::Object{{"source", "a test"}}));
    const cli::RunConfig read = cli::read_run_config(config);
    EXPECT_EQ(read.sequence, written.sequence);
    const FusionSpec &a = read.fusion, &b = written.fusion;
    EXPECT_TRUE(a.method == b.method && a.wavelet == b.wavelet && a.levels == b.levels && a.mode == b.mode &&
                a.base_rule == b.base_rule && a.detail_rule == b.detail_rule)
        << read_bytes(config);

    const CliResult run = run_cli({"run", "--config", config, "--cycles", "1", "--virtual-clock", "--backend", "cpu",
                                   "--background-frames", "0", "--out", tmp.file("o"), "--record", tmp.file("rec")});
    ASSERT_EQ(run.status, 0) << run.err;
    const Dataset d = read_dataset(tmp.file("rec"));
    std::vector<std::string> frames;
    for (const Illumination& setting : written.sequence)
        for (const DatasetTake& take : d.sensors.at(0).takes)
            for (const DatasetFrame& f : take.frames)
                if (!take.background && f.illumination == setting) frames.push_back(tmp.file("rec/" + f.file));
    ASSERT_EQ(frames.size(), 3u);
    // run writes 8-bit PNGs: within half a level of the float fusion (a
    // sample within float rounding of a half level may round either way).
    const Image fused_by_run = io::read_image(tmp.file("o/fused/SIM-0001/000000.png"));
    const auto distance_to = [&](const std::string& base, const std::string& detail) {
        std::vector<std::string> args{"fuse", "--backend", "cpu", "--method", "wavelet", "--wavelet", "db2",
                                      "--levels", "2", "--mode", "symmetric", "--base-rule", base, "--detail-rule",
                                      detail, "-o", tmp.file("f.npy")};
        args.insert(args.end(), frames.begin(), frames.end());
        const CliResult r = run_cli(args);
        EXPECT_EQ(r.status, 0) << r.err;
        const Image f = io::read_image(tmp.file("f.npy"));
        double worst = 0;
        for (std::size_t i = 0; i < f.data.size(); ++i)
            worst = std::max(worst, std::abs(double(fused_by_run.data.at(i)) -
                                             std::clamp(double(f.data[i]), 0.0, 1.0)));
        return worst;
    };
    EXPECT_LE(distance_to("max", "min"), 0.5 / 255 + 1e-5);
    EXPECT_GT(distance_to("min", "max"), 4.0 / 255);
    EXPECT_GT(distance_to("mean", "max-abs"), 4.0 / 255);
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
    // A misspelt key would leave the default in force; of a key given twice, one would win.
    refused(R"({"format": "vkfuse-config", "version": 1, "sequence": "15,15,15", "sequnce": "0,15,0"})",
            "unknown key \"sequnce\" (expected format, version, sequence, method, wavelet, levels, mode, base_rule, "
            "detail_rule, tuned)");
    refused(R"({"format": "vkfuse-config", "version": 1, "sequence": "15,15,15", "sequence": "0,15,0"})",
            "\"sequence\" given twice");
    // A cycle of 1000 settings would run for minutes per cycle.
    std::string long_sequence = "15,15,15";
    for (int i = 1; i < 1000; ++i) long_sequence += "+0," + std::to_string(i % 16) + ",0";
    refused(R"({"format": "vkfuse-config", "version": 1, "sequence": ")" + long_sequence + "\"}",
            "more than 16 settings in one cycle");
    const CliResult too_long = run_cli({"run", "--sequence", long_sequence, "--cycles", "1", "--virtual-clock"});
    EXPECT_EQ(too_long.status, 2);
    ASSERT_EQ(too_long.err_lines().size(), 1u) << too_long.err;
    EXPECT_NE(too_long.err.find("more than 16 settings in one cycle"), std::string::npos) << too_long.err;
    EXPECT_LT(too_long.err.size(), 300u) << too_long.err;
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
    // The study's own bounds: 5^3 settings, and 4^3 settings in up to 5 make
    // more than a million combinations.
    refused({"tune", "--simulate", "--grid", "0,1,2,3,15", "--max-k", "2", "--out", tmp.file("a.json")},
            "tune: --grid 0,1,2,3,15 --max-k 2: 125 settings, more than a study takes (64)");
    refused({"tune", "--simulate", "--grid", "0,1,5,15", "--max-k", "5", "--out", tmp.file("a.json")},
            "tune: --grid 0,1,5,15 --max-k 5: 64 settings in combinations of up to 5 make more than 1000000");
    refused({"tune", "--simulate", "--objects", "coin,lego,coin", "--out", tmp.file("a.json")},
            "object \"coin\" named twice");
    EXPECT_FALSE(std::filesystem::exists(tmp.file("a.json")));
}

}  // namespace
}  // namespace vkfuse::test

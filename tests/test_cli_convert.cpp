// A dataset's MCAP form through the commands: `vkfuse sim --out x.mcap` holds
// what the folder holds (convert gives back the very files), `vkfuse study`
// scores a recording as it scores its folder, and bad recordings or targets
// get one line and leave nothing behind.
#include <gtest/gtest.h>

#include <fstream>

#include "cli_runner.hpp"
#include "study_dataset.hpp"

namespace vkfuse::test {
namespace {

bool has(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

TEST(CliConvert, SimAsMcapConvertsToTheFilesSimWritesAsAFolder) {
    TempDir tmp;
    const std::vector<std::string> sim = {"sim", "--objects", "coin,lego", "--grid", "0,15", "--frames", "2",
                                          "--background-frames", "1", "--seed", "7"};
    auto with_out = [&](const std::string& out) {
        std::vector<std::string> args = sim;
        args.insert(args.end(), {"--out", out});
        return args;
    };
    ASSERT_EQ(run_cli(with_out(tmp.file("set"))).status, 0);
    const CliResult m = run_cli(with_out(tmp.file("set.mcap")));
    ASSERT_EQ(m.status, 0) << m.err;
    const CliResult c = run_cli({"convert", tmp.file("set.mcap"), tmp.file("back")});
    ASSERT_EQ(c.status, 0) << c.err;
    EXPECT_TRUE(has(c.out, "back: 1 sensors, 40 frames, 0 missed cycles (from ")) << c.out;
    const std::vector<std::string> files = files_under(tmp.file("set"));
    ASSERT_EQ(files, files_under(tmp.file("back")));
    for (const std::string& f : files)
        EXPECT_EQ(read_bytes(tmp.file("set/" + f)), read_bytes(tmp.file("back/" + f))) << f;
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"back", "set", "set.mcap"}));  // nothing staged left over
}

TEST(CliConvert, AStudyOfARecordingIsTheStudyOfItsFolder) {
    TempDir tmp;
    write_study_dataset(tmp.file("set"));
    write_study_dataset(tmp.file("set.mcap"));
    const std::vector<std::string> args = {"--max-k", "2", "--greedy-max", "3", "--top", "3", "--methods", "brovey,laplacian"};
    std::string results[2];
    int i = 0;
    for (const char* set : {"set", "set.mcap"}) {
        std::vector<std::string> study = {"study", tmp.file(set), "--out", tmp.file(std::string(set) + "-study")};
        study.insert(study.end(), args.begin(), args.end());
        const CliResult r = run_cli(study);
        ASSERT_EQ(r.status, 0) << r.err;
        std::string text = read_bytes(tmp.file(std::string(set) + "-study/results.json"));
        text.erase(text.find("\"seconds\""));  // the one wall-clock figure, written last
        const std::size_t path = text.find("\"dataset\": ");  // the path given, which differs
        ASSERT_NE(path, std::string::npos);
        text.erase(path, text.find('\n', path) - path);
        results[i++] = text;
    }
    EXPECT_EQ(results[0], results[1]);
}

TEST(CliConvert, BadRecordingsAndTargetsGetOneLineAndNothingWritten) {
    TempDir tmp;
    std::ofstream(tmp.file("junk.mcap")) << "not an mcap file at all, but long enough";
    std::ofstream(tmp.file("taken.mcap")) << "x";
    write_study_dataset(tmp.file("set"));
    const struct {
        std::vector<std::string> args;
        std::string fragment;
    } cases[] = {
        {{"convert", tmp.file("junk.mcap"), tmp.file("out")}, "junk.mcap: not an MCAP file (no MCAP magic at its start)"},
        {{"convert", tmp.file("missing.mcap"), tmp.file("out")}, "missing.mcap: cannot open"},
        {{"convert", tmp.file("set"), tmp.file("taken.mcap")}, "taken.mcap: exists (name a new file)"},
        {{"convert", "--compression", "brotli", tmp.file("set"), tmp.file("x.mcap")}, "--compression brotli"},
        {{"convert", "--compression", "lz4", tmp.file("set"), tmp.file("folder")}, "is a folder"},
        {{"convert", tmp.file("set")}, "expected IN and OUT"},
        {{"run", "--replay", tmp.file("junk.mcap"), "--out", tmp.file("out")}, "junk.mcap: not an MCAP file"},
        {{"run", "--virtual-clock", "--cycles", "1", "--record", tmp.file("taken.mcap")}, "taken.mcap: exists"},
        {{"study", tmp.file("junk.mcap"), "--out", tmp.file("out")}, "junk.mcap: not an MCAP file"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.args[0] + " " + c.args[1]);
        const CliResult r = run_cli(c.args);
        EXPECT_EQ(r.status, 2);
        ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
        EXPECT_TRUE(has(r.err, c.fragment)) << r.err;
    }
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"junk.mcap", "set", "taken.mcap"}));
    EXPECT_EQ(read_bytes(tmp.file("taken.mcap")), "x");
}

}  // namespace
}  // namespace vkfuse::test

// vkfuse run against hostile datasets and unlucky users: nothing is written
// outside --out whatever a replayed manifest says, no existing file is
// touched, a failing run changes nothing, and the output directory holds one
// whole run or nothing.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "cli_runner.hpp"

namespace vkfuse::test {
namespace {

namespace fs = std::filesystem;

bool has(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

std::size_t count_lines(const std::string& text) { return std::size_t(std::count(text.begin(), text.end(), '\n')); }

// Every file under dir (links included, not followed) with its bytes: a
// snapshot to compare before and after a command.
std::vector<std::pair<std::string, std::string>> snapshot(const std::string& dir) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        const std::string rel = fs::relative(e.path(), dir).string();
        if (e.is_symlink())
            out.emplace_back(rel, "-> " + fs::read_symlink(e.path()).string());
        else if (e.is_regular_file())
            out.emplace_back(rel, read_bytes(e.path().string()));
        else
            out.emplace_back(rel + "/", "");
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::string> run_args(const TempDir& tmp, const std::string& out, int cycles) {
    return {"run",           "--virtual-clock", "--cycles", std::to_string(cycles), "--background-frames",
            "1",             "--method",        "brovey",   "--backend",            "cpu",
            "--out",         tmp.file(out)};
}

// A small recorded run (1 sensor, 2 cycles) to tamper with.
std::string record(const TempDir& tmp, const std::string& name = "rec") {
    std::vector<std::string> args = run_args(tmp, name + "-out", 2);
    args.insert(args.end(), {"--record", tmp.file(name)});
    const CliResult r = run_cli(args);
    if (r.status != 0) throw std::runtime_error("recording failed: " + r.err);
    return tmp.file(name);
}

void replace_in_file(const std::string& path, const std::string& from, const std::string& to) {
    std::string text = read_bytes(path);
    const std::size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error(path + ": no " + from);
    write_bytes(path, text.replace(at, from.size(), to));
}

// The first frame file of the object take, as the manifest lists it.
std::string first_object_frame(const std::string& dataset) {
    const std::string text = read_bytes(dataset + "/manifest.json");
    const std::size_t take = text.find("\"object\": \"coin\"");
    const std::size_t file = text.find("\"file\": \"", take) + 9;
    return text.substr(file, text.find('"', file) - file);
}

void expect_one_line_failure(const CliResult& r, const std::string& fragment) {
    EXPECT_EQ(r.status, 2) << r.err;
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_TRUE(has(r.err, fragment)) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(CliRunHostile, AbsoluteSerialInAManifestWritesNothingAnywhere) {
    TempDir tmp;
    const std::string rec = record(tmp);
    const std::string elsewhere = tmp.file("elsewhere");
    replace_in_file(rec + "/manifest.json", "\"serial\": \"SIM-0001\"", "\"serial\": \"" + elsewhere + "\"");
    const CliResult r = run_cli({"run", "--replay", rec, "--backend", "cpu", "--out", tmp.file("o")});
    expect_one_line_failure(r, "sensors[0].serial: \"" + elsewhere + "\": not usable as a file name");
    EXPECT_FALSE(fs::exists(elsewhere));
    EXPECT_FALSE(fs::exists(tmp.file("o")));
}

TEST(CliRunHostile, ObjectNameThatClimbsOutIsRefused) {
    TempDir tmp;
    const std::string rec = record(tmp);
    replace_in_file(rec + "/manifest.json", "\"object\": \"coin\"", "\"object\": \"../../../pwn\"");
    const CliResult r =
        run_cli({"run", "--replay", rec, "--object", "../../../pwn", "--backend", "cpu", "--out", tmp.file("a/b/o")});
    expect_one_line_failure(r, "\"../../../pwn\": not usable as a file name");
    EXPECT_FALSE(fs::exists(tmp.file("pwn_SIM-0001.png")));
    EXPECT_FALSE(fs::exists(tmp.file("a/b/o")));
}

// A manifest's frame size never chooses how much memory a replay takes: the
// rig's need is checked from the manifest before any buffer is sized.
TEST(CliRunHostile, HugeFrameSizeInAManifestIsRefusedUpFront) {
    TempDir tmp;
    const std::string rec = record(tmp);
    // 65536 x 65536: were the check gone, the first allocation (100 GiB of
    // double) fails at once instead of paging the machine to death.
    replace_in_file(rec + "/manifest.json", "\"width\": 320", "\"width\": 65536");
    replace_in_file(rec + "/manifest.json", "\"height\": 240", "\"height\": 65536");
    const CliResult r = run_cli({"run", "--replay", rec, "--backend", "cpu", "--out", tmp.file("o")},
                                {"VKFUSE_MEMORY_LIMIT=1G"});
    expect_one_line_failure(r, rec + "/manifest.json: replaying needs about ");
    EXPECT_TRUE(has(r.err, "GiB of memory, 1.0 GiB available (VKFUSE_MEMORY_LIMIT)")) << r.err;
    EXPECT_FALSE(fs::exists(tmp.file("o")));
}

// "000040..png" holds ".." but no ".." component: an ordinary name.
TEST(CliRunHostile, DotsInsideANameAreNotATraversal) {
    TempDir tmp;
    const std::string rec = record(tmp);
    const std::string frame = first_object_frame(rec);
    const std::string renamed = frame.substr(0, frame.size() - 4) + "..png";
    fs::rename(rec + "/" + frame, rec + "/" + renamed);
    replace_in_file(rec + "/manifest.json", "\"" + frame + "\"", "\"" + renamed + "\"");
    const CliResult r = run_cli({"run", "--replay", rec, "--backend", "cpu", "--out", tmp.file("o")});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count_lines(read_bytes(tmp.file("o/metrics.jsonl"))), 2u);
}

TEST(CliRunHostile, FramePathsWithDotDotComponentsAreRefused) {
    TempDir tmp;
    const std::string rec = record(tmp);
    const std::string frame = first_object_frame(rec);
    replace_in_file(rec + "/manifest.json", "\"" + frame + "\"", "\"SIM-0001/../../rec-out/summary.json\"");
    const CliResult r = run_cli({"run", "--replay", rec, "--backend", "cpu", "--out", tmp.file("o")});
    expect_one_line_failure(r, "expected a relative path inside the dataset");
}

TEST(CliRunHostile, SymbolicLinkLeadingOutOfTheDatasetIsRefused) {
    TempDir tmp;
    const std::string rec = record(tmp);
    const std::string frame = rec + "/" + first_object_frame(rec);
    const std::string outside = tmp.file("outside.png");
    fs::copy_file(frame, outside);
    fs::remove(frame);
    fs::create_symlink(outside, frame);
    const CliResult r = run_cli({"run", "--replay", rec, "--backend", "cpu", "--out", tmp.file("o")});
    expect_one_line_failure(r, "leads outside " + rec + " (symbolic link)");
    EXPECT_FALSE(fs::exists(tmp.file("o")));
}

// A link planted where the run writes is never opened, so its target keeps
// its bytes; --replace swaps the whole directory and drops the link itself.
TEST(CliRunHostile, PlantedSymlinkIsNotFollowed) {
    TempDir tmp;
    const std::string victim = tmp.file("victim.txt");
    write_bytes(victim, "precious\n");
    fs::create_directory(tmp.file("o"));
    fs::create_symlink(victim, tmp.file("o/metrics.jsonl"));
    const CliResult refused = run_cli(run_args(tmp, "o", 1));
    expect_one_line_failure(refused, "--out " + tmp.file("o") + ": exists and is not empty");
    std::vector<std::string> replace = run_args(tmp, "o", 1);
    replace.push_back("--replace");
    const CliResult replaced = run_cli(replace);
    ASSERT_EQ(replaced.status, 0) << replaced.err;
    EXPECT_EQ(read_bytes(victim), "precious\n");
    EXPECT_FALSE(fs::is_symlink(tmp.file("o/metrics.jsonl")));
    EXPECT_EQ(count_lines(read_bytes(tmp.file("o/metrics.jsonl"))), 1u);
}

TEST(CliRunHostile, OutAsASymlinkIsRefused) {
    TempDir tmp;
    fs::create_directory(tmp.file("real"));
    fs::create_directory_symlink(tmp.file("real"), tmp.file("o"));
    expect_one_line_failure(run_cli(run_args(tmp, "o", 1)), "is a symbolic link");
    EXPECT_TRUE(fs::is_empty(tmp.file("real")));
}

// A run that fails (here: --record names a used directory) leaves the earlier
// run's files exactly as they were, and no staging directory behind.
TEST(CliRunUnlucky, AFailingRunKeepsThePreviousResults) {
    TempDir tmp;
    ASSERT_EQ(run_cli(run_args(tmp, "prev", 3)).status, 0);
    fs::create_directory(tmp.file("used"));
    write_bytes(tmp.file("used/x"), "x");
    const auto before = snapshot(tmp.file("prev"));
    std::vector<std::string> args = run_args(tmp, "prev", 1);
    args.insert(args.end(), {"--replace", "--record", tmp.file("used")});
    expect_one_line_failure(run_cli(args), "--record " + tmp.file("used") + ": exists and is not empty");
    EXPECT_EQ(snapshot(tmp.file("prev")), before);
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"prev", "used"}));
}

// Runs never mix in one --out: without --replace a used one is refused; with
// it the directory holds the new run alone (no earlier fused frame left).
TEST(CliRunUnlucky, ASecondRunReplacesOrIsRefused) {
    TempDir tmp;
    ASSERT_EQ(run_cli(run_args(tmp, "o", 3)).status, 0);
    const auto first = snapshot(tmp.file("o"));
    expect_one_line_failure(run_cli(run_args(tmp, "o", 1)), "add --replace to replace it");
    EXPECT_EQ(snapshot(tmp.file("o")), first);
    std::vector<std::string> args = run_args(tmp, "o", 1);
    args.push_back("--replace");
    const CliResult r = run_cli(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count_lines(read_bytes(tmp.file("o/metrics.jsonl"))), 1u);
    std::size_t fused = 0;
    for (const auto& e : fs::directory_iterator(tmp.file("o/fused/SIM-0001"))) fused += e.is_regular_file();
    EXPECT_EQ(fused, 1u);
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"o"}));
}

// --replace never deletes a directory vkfuse run did not write.
TEST(CliRunUnlucky, ReplaceRefusesAForeignDirectory) {
    TempDir tmp;
    fs::create_directory(tmp.file("home"));
    write_bytes(tmp.file("home/thesis.tex"), "years of work");
    std::vector<std::string> args = run_args(tmp, "home", 1);
    args.push_back("--replace");
    expect_one_line_failure(run_cli(args), "holds thesis.tex, which this command does not write");
    EXPECT_EQ(read_bytes(tmp.file("home/thesis.tex")), "years of work");
}

TEST(CliRunUnlucky, EmptyExistingOutIsUsed) {
    TempDir tmp;
    fs::create_directory(tmp.file("o"));
    ASSERT_EQ(run_cli(run_args(tmp, "o", 1)).status, 0);
    EXPECT_TRUE(fs::exists(tmp.file("o/summary.json")));
}

// Without --out, stdout carries the only result: a failed write is a failure.
TEST(CliRunUnlucky, SummaryToAFullDeviceFails) {
    if (::access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no /dev/full";
    const std::string command = std::string(VKFUSE_CLI) +
                                " run --virtual-clock --cycles 1 --background-frames 1 --backend cpu >/dev/full 2>&1";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
}

// Seconds far beyond what int64 nanoseconds hold mean "wait as long as it
// takes", not "time out at once".
TEST(CliRunUnlucky, HugeTimeoutDoesNotOverflow) {
    TempDir tmp;
    std::vector<std::string> args = run_args(tmp, "o", 2);
    args.insert(args.end(), {"--timeout", "1e10"});
    const CliResult r = run_cli(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(has(r.out, "\"fused\": 2,")) << r.out;
    EXPECT_TRUE(has(r.out, "\"errors\": []")) << r.out;
}

// SIGTERM (timeout, systemd, docker) ends the run like Ctrl-C: the cycle in
// hand finishes, --out appears whole and the --record dataset has its manifest.
TEST(CliRunUnlucky, SigtermFinishesTheRunAndTheRecording) {
    TempDir tmp;
    const pid_t pid = start_cli({"run", "--virtual-clock", "--background-frames", "1", "--method", "brovey",
                                 "--backend", "cpu", "--out", tmp.file("o"), "--record", tmp.file("rec")},
                                tmp.file("stdout"), tmp.file("stderr"));
    // The run writes into a hidden staging directory beside --out: wait for
    // two metrics lines there.
    auto staged_lines = [&] {
        const std::string staging = staging_directory(tmp.file(""), "metrics.jsonl");
        return staging.empty()
                   ? std::size_t(0)
                   : count_lines(read_bytes(staging + "/metrics.jsonl"));
    };
    for (int i = 0; i < 600 && staged_lines() < 2; ++i) usleep(100000);
    kill(pid, SIGTERM);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 0);
    const std::size_t cycles = count_lines(read_bytes(tmp.file("o/metrics.jsonl")));
    EXPECT_GE(cycles, 2u);
    EXPECT_TRUE(has(read_bytes(tmp.file("stderr")),
                    "vkfuse run: interrupted after " + std::to_string(cycles) + " cycles; wrote what they fused\n"))
        << read_bytes(tmp.file("stderr"));
    EXPECT_EQ(read_bytes(tmp.file("o/summary.json")), read_bytes(tmp.file("stdout")));
    ASSERT_TRUE(fs::exists(tmp.file("rec/manifest.json")));
    const CliResult replay = run_cli({"run", "--replay", tmp.file("rec"), "--backend", "cpu", "--out", tmp.file("b")});
    ASSERT_EQ(replay.status, 0) << replay.err;
    EXPECT_EQ(read_bytes(tmp.file("b/metrics.jsonl")), read_bytes(tmp.file("o/metrics.jsonl")));
}

// A sensor that missed a cycle when recorded misses the same cycle in the
// replay: frames are placed by their recorded cycle, not by setting, so no
// cycle shifts and none is dropped.
TEST(CliRunUnlucky, ReplayKeepsARecordedTimeoutInItsCycle) {
    TempDir tmp;
    std::vector<std::string> live = run_args(tmp, "live", 4);
    live.insert(live.end(), {"--sensors", "2", "--record", tmp.file("rec")});
    ASSERT_EQ(run_cli(live).status, 0);
    // As if SIM-0002 had timed out in cycle 1: its frames of that cycle gone,
    // the miss recorded the way `vkfuse run --record` records one.
    const std::string manifest = tmp.file("rec/manifest.json");
    std::string kept;
    std::size_t dropped = 0;
    for (std::size_t start = 0, end; (end = read_bytes(manifest).find('\n', start)) != std::string::npos;
         start = end + 1) {
        const std::string line = read_bytes(manifest).substr(start, end - start + 1);
        const bool miss = has(line, "\"file\": \"SIM-0002/coin/") && has(line, "\"cycle\": 1}");
        dropped += miss;
        if (!miss) kept += line;
    }
    ASSERT_EQ(dropped, 2u);
    const std::string error = "SIM-0002: no frames within 5.000000 s (cycle 1)";
    write_bytes(manifest, kept);
    replace_in_file(manifest, "\"serial\": \"SIM-0002\",",
                    "\"serial\": \"SIM-0002\", \"missed\": [{\"cycle\": 1, \"status\": \"timeout\", \"error\": \"" +
                        error + "\"}],");
    const CliResult r = run_cli({"run", "--replay", tmp.file("rec"), "--backend", "cpu", "--out", tmp.file("again")});
    ASSERT_EQ(r.status, 0) << r.err;
    std::string expected;
    const std::string recorded = read_bytes(tmp.file("live/metrics.jsonl"));
    for (std::size_t start = 0, end; (end = recorded.find('\n', start)) != std::string::npos; start = end + 1) {
        const std::string line = recorded.substr(start, end - start + 1);
        expected += has(line, "{\"cycle\": 1, \"sensor\": \"SIM-0002\"")
                        ? "{\"cycle\": 1, \"sensor\": \"SIM-0002\", \"status\": \"timeout\", \"error\": \"" + error +
                              "\"}\n"
                        : line;
    }
    EXPECT_EQ(read_bytes(tmp.file("again/metrics.jsonl")), expected);
    for (const char* f : {"SIM-0001/000001.png", "SIM-0002/000000.png", "SIM-0002/000002.png", "SIM-0002/000003.png"})
        EXPECT_TRUE(read_bytes(tmp.file(std::string("again/fused/") + f)) ==
                    read_bytes(tmp.file(std::string("live/fused/") + f)))
            << f << " differs from the recorded run's";
    EXPECT_FALSE(fs::exists(tmp.file("again/fused/SIM-0002/000001.png")));
}

// An interrupted `vkfuse sim` leaves neither the dataset nor its staging directory.
TEST(CliRunUnlucky, InterruptedSimLeavesNothing) {
    TempDir tmp;
    const pid_t pid =
        start_cli({"sim", "--out", tmp.file("set"), "--frames", "4"}, "/dev/null", tmp.file("stderr"));
    auto staged_files = [&] {
        std::size_t n = 0;
        const std::string staging = staging_directory(tmp.file(""));
        if (!staging.empty())
            for (const auto& f : fs::recursive_directory_iterator(staging)) n += f.is_regular_file();
        return n;
    };
    for (int i = 0; i < 600 && staged_files() < 3; ++i) usleep(50000);
    kill(pid, SIGINT);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 2);
    EXPECT_TRUE(has(read_bytes(tmp.file("stderr")), "--out " + tmp.file("set") + ": interrupted; nothing written"));
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"stderr"});
}

// "o/" names the directory o: staged beside it and published as o. A trailing
// slash neither bypasses the symlink check nor lets --record alias --out.
TEST(CliRunUnlucky, TrailingSlashesNameTheSameDirectory) {
    TempDir tmp;
    std::vector<std::string> args = run_args(tmp, "o", 1);
    args.back() += "/";
    const CliResult r = run_cli(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count_lines(read_bytes(tmp.file("o/metrics.jsonl"))), 1u);
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"o"});

    fs::create_directory(tmp.file("real"));
    fs::create_directory_symlink(tmp.file("real"), tmp.file("link"));
    args = run_args(tmp, "link", 1);
    args.back() += "/";
    expect_one_line_failure(run_cli(args), "is a symbolic link");

    args = run_args(tmp, "p", 1);
    args.back() += "/";
    args.insert(args.end(), {"--record", tmp.file("./p")});
    expect_one_line_failure(run_cli(args), ": the same directory as --out");
    EXPECT_FALSE(fs::exists(tmp.file("p")));

    for (const std::string dot : {".", "..", "/"}) {
        const CliResult bad = run_cli({"run", "--virtual-clock", "--cycles", "1", "--out", dot});
        expect_one_line_failure(bad, "--out " + dot + ": name a directory of its own");
    }
}

}  // namespace
}  // namespace vkfuse::test

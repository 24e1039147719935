// `vkfuse fuse` and `vkfuse metrics` against hostile files and hostile
// surroundings (issue 11), end to end: output modes follow the umask or the
// replaced file, long output names work, a huge sparse input is refused at
// once, a command that cannot fit in memory says so from the headers naming
// its inputs, a full disk or a file-size limit is one line and exit 2, an
// interrupted fuse leaves no temporary, and a path that is not UTF-8 still
// gives valid JSON.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <thread>

#include "cli_runner.hpp"
#include "io/json_value.hpp"
#include "io_test_files.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

using Clock = std::chrono::steady_clock;

// /bin/sh -c script, with $VKFUSE naming the binary: for limits (ulimit) that
// must apply to the command alone.
CliResult run_shell(const std::string& script, const std::vector<std::string>& extra_env = {}) {
    TempDir capture;
    const std::string out_path = capture.file("stdout"), err_path = capture.file("stderr");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> words{"/bin/sh", "-c", script};
    std::vector<std::string> extra = extra_env;
    extra.push_back(std::string("VKFUSE=") + VKFUSE_CLI);
    std::vector<std::string> env = environment_with(extra);
    std::vector<char*> argv = c_strings(words), envp = c_strings(env);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, "/bin/sh", &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start /bin/sh");
    int wstatus = 0;
    ::waitpid(pid, &wstatus, 0);
    CliResult result;
    result.status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
    result.out = read_bytes(out_path);
    result.err = read_bytes(err_path);
    return result;
}

void expect_one_line_failure(const CliResult& r, const std::string& fragment) {
    EXPECT_EQ(r.status, 2) << r.err;
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("vkfuse: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

// Two small frames to fuse.
void write_frames(const TempDir& dir) {
    io::write_image(dir.file("a.npy"), convert<float>(structured_image(24, 32, 3, 1)));
    io::write_image(dir.file("b.npy"), convert<float>(structured_image(24, 32, 3, 2)));
}

CliResult fuse_into(const TempDir& dir, const std::string& output, std::vector<std::string> extra_env = {}) {
    return run_cli({"fuse", "--backend", "cpu", "--method", "brovey", "-o", output, dir.file("a.npy"),
                    dir.file("b.npy")},
                   extra_env);
}

TEST(CliOutputModes, UmaskIsFollowed) {
    TempDir dir;
    write_frames(dir);
    {
        Umask mask(077);
        ASSERT_EQ(fuse_into(dir, dir.file("private.png")).status, 0);
        ASSERT_EQ(fuse_into(dir, dir.file("private.npy")).status, 0);
    }
    EXPECT_EQ(mode_of(dir.file("private.png")), 0600u);
    EXPECT_EQ(mode_of(dir.file("private.npy")), 0600u);
}

TEST(CliOutputModes, ReplacedFileKeepsItsMode) {
    TempDir dir;
    write_frames(dir);
    Umask mask(022);
    write_bytes(dir.file("secret.png"), "previous");
    ASSERT_EQ(::chmod(dir.file("secret.png").c_str(), 0600), 0);
    CliResult r = fuse_into(dir, dir.file("secret.png"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(mode_of(dir.file("secret.png")), 0600u);
    EXPECT_NE(read_bytes(dir.file("secret.png")), "previous");
}

TEST(CliOutputNames, NamesUpTo255BytesWork) {
    TempDir dir;
    write_frames(dir);
    for (std::size_t length : {244u, 250u, 255u}) {
        SCOPED_TRACE(length);
        const std::string out = dir.file(std::string(length - 4, 'x') + ".png");
        CliResult r = fuse_into(dir, out);
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_TRUE(std::filesystem::exists(out));
    }
    EXPECT_EQ(dir.entries().size(), 5u);  // a.npy, b.npy and the three outputs, nothing else
}

// "000040..png" holds ".." but is one ordinary file name.
TEST(CliOutputNames, DotsInANameAreNotATraversal) {
    TempDir dir;
    write_frames(dir);
    const std::string out = dir.file("000040..png");
    ASSERT_EQ(fuse_into(dir, out).status, 0);
    CliResult r = run_cli({"metrics", "--backend", "cpu", out});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("000040..png"), std::string::npos);
}

TEST(CliHugeInputs, TerabyteSparseNpyIsRefusedAtOnce) {
    TempDir dir;
    const std::string path = dir.file("huge.npy");
    write_sparse(path, npy_header_only(16, 16, 3), kTerabyte);
    const auto start = Clock::now();
    CliResult r = run_cli({"metrics", "--backend", "cpu", path});
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
    expect_one_line_failure(r, path + ": corrupt: header says 16x16x3 float32");
}

TEST(CliHugeInputs, TerabyteSparsePngIsReadOnlyToItsEnd) {
    TempDir dir;
    const std::string path = dir.file("tail.png");
    write_sparse(path, zero_png(40, 30), kTerabyte);
    const auto start = Clock::now();
    CliResult r = run_cli({"metrics", "--backend", "cpu", path});
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"sharpness\": 0"), std::string::npos) << r.out;
}

// Two 16384 x 16384 headers in 270 kB each: 1 GiB of float apiece once
// decoded, several GiB to fuse. The refusal comes from the headers, names both
// inputs and both figures. The shell's ulimit -v keeps a regression from
// taking the machine's memory: it is an allocation failure then, not an OOM kill.
class CliMemory : public ::testing::Test {
protected:
    void SetUp() override {
#if defined(__SANITIZE_ADDRESS__)
        // The binary under test is built like this test: ASan reserves
        // terabytes of shadow address space at start, which any ulimit -v
        // forbids. The release build's run of these tests is the one that counts.
        GTEST_SKIP() << "an AddressSanitizer build cannot start under ulimit -v";
#endif
        write_bytes(dir.file("a.png"), fake_huge_png(16384, 270000));
        write_bytes(dir.file("b.png"), fake_huge_png(16384, 270000));
    }
    CliResult run(const std::string& args, const std::string& limit = "1G") {
        return run_shell("ulimit -v 3000000; exec \"$VKFUSE\" " + args, {"VKFUSE_MEMORY_LIMIT=" + limit});
    }
    TempDir dir;
};

TEST_F(CliMemory, FuseRefusesFromTheHeadersNamingTheInputs) {
    for (const std::string backend : {"cpu", "auto"}) {
        SCOPED_TRACE(backend);
        const auto start = Clock::now();
        CliResult r = run("fuse --method laplacian --backend " + backend + " -o " + dir.file("out.png") + " " +
                          dir.file("a.png") + " " + dir.file("b.png"));
        EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 2.0);
        expect_one_line_failure(r, dir.file("a.png") + ", " + dir.file("b.png") + ": fusing needs about ");
        EXPECT_NE(r.err.find(" GiB of memory, 1.0 GiB available (VKFUSE_MEMORY_LIMIT)"), std::string::npos) << r.err;
    }
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.png", "b.png"}));
}

TEST_F(CliMemory, MetricsRefusesFromTheHeadersNamingTheInputs) {
    CliResult r = run("metrics --backend cpu --background " + dir.file("b.png") + " " + dir.file("a.png"));
    expect_one_line_failure(r, dir.file("a.png") + ", " + dir.file("b.png") + ": scoring needs about ");
    EXPECT_NE(r.err.find("1.0 GiB available (VKFUSE_MEMORY_LIMIT)"), std::string::npos) << r.err;
}

// Without the variable the process's own limits count: here RLIMIT_AS.
TEST_F(CliMemory, AnAddressSpaceLimitCounts) {
    CliResult r = run_shell("ulimit -v 2000000; exec \"$VKFUSE\" fuse --method brovey --backend cpu -o " +
                            dir.file("out.npy") + " " + dir.file("a.png") + " " + dir.file("b.png"));
    expect_one_line_failure(r, ": fusing needs about ");
    EXPECT_NE(r.err.find("available (RLIMIT_AS)"), std::string::npos) << r.err;
}

TEST_F(CliMemory, AMalformedLimitIsAnError) {
    CliResult r = run("fuse --method brovey -o " + dir.file("out.npy") + " " + dir.file("a.png"), "lots");
    expect_one_line_failure(r, "VKFUSE_MEMORY_LIMIT=lots: expected a byte count");
}

TEST(CliFullDisk, DevFullOutputFailsWithOneLine) {
    TempDir dir;
    write_frames(dir);
    for (const char* name : {"full.npy", "full.png"}) {
        const std::string link = dir.file(name);
        std::filesystem::create_symlink("/dev/full", link);
        expect_one_line_failure(fuse_into(dir, link), link + ": cannot write: No space left on device");
        EXPECT_TRUE(std::filesystem::is_symlink(link));
    }
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.npy", "b.npy", "full.npy", "full.png"}));
}

// ulimit -f 64: the kernel stops the file at 32 KiB (dash counts 512-byte
// blocks; bash 1 KiB: 64 KiB). vkfuse ignores SIGXFSZ, so
// that is a write error naming the output rather than death by signal.
TEST(CliFullDisk, FileSizeLimitFailsWithOneLineAndLeavesNothing) {
    TempDir dir;
    write_frames(dir);
    write_bytes(dir.file("out.npy"), "the previous result");
    CliResult r = run_shell("ulimit -f 64; exec \"$VKFUSE\" fuse --backend cpu --method brovey -o " +
                            dir.file("out.npy") + " " + dir.file("a.npy") + " " + dir.file("b.npy"));
    EXPECT_EQ(r.status, 0) << "24x32x3 floats fit: " << r.err;
    io::write_image(dir.file("a.npy"), convert<float>(structured_image(96, 64, 3, 1)));
    io::write_image(dir.file("b.npy"), convert<float>(structured_image(96, 64, 3, 2)));
    write_bytes(dir.file("out.npy"), "the previous result");
    r = run_shell("ulimit -f 64; exec \"$VKFUSE\" fuse --backend cpu --method brovey -o " + dir.file("out.npy") + " " +
                  dir.file("a.npy") + " " + dir.file("b.npy"));
    expect_one_line_failure(r, dir.file("out.npy") + ": cannot write: File too large");
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.npy", "b.npy", "out.npy"}));
    EXPECT_EQ(read_bytes(dir.file("out.npy")), "the previous result");
}

// SIGTERM at moments spread over a fuse's run (reading, fusing, writing,
// fsync): whenever it lands, no temporary is left; the output is either the
// old file or the whole new one.
TEST(CliInterrupt, SigtermAtAnyMomentLeavesNoTemporary) {
    TempDir dir;
    io::write_image(dir.file("a.npy"), convert<float>(structured_image(600, 800, 3, 1)));
    io::write_image(dir.file("b.npy"), convert<float>(structured_image(600, 800, 3, 2)));
    const std::vector<std::string> args{VKFUSE_CLI, "fuse", "--backend", "cpu", "--method", "brovey", "-o",
                                        dir.file("out.png"), dir.file("a.npy"), dir.file("b.npy")};
    auto start_fuse = [&] {
        std::vector<std::string> words = args;
        std::vector<char*> argv = c_strings(words);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
        pid_t pid = 0;
        posix_spawn(&pid, VKFUSE_CLI, &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        return pid;
    };
    // How long one run takes here, to spread the signals over it.
    const auto t0 = Clock::now();
    int status = 0;
    ::waitpid(start_fuse(), &status, 0);
    const auto full = Clock::now() - t0;
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    const std::string complete = read_bytes(dir.file("out.png"));
    int interrupted = 0;
    for (int i = 1; i <= 12; ++i) {
        std::filesystem::remove(dir.file("out.png"));
        const pid_t pid = start_fuse();
        std::this_thread::sleep_for(full * i / 13);
        ::kill(pid, SIGTERM);
        ::waitpid(pid, &status, 0);
        interrupted += WIFSIGNALED(status);
        SCOPED_TRACE(i);
        std::vector<std::string> expected{"a.npy", "b.npy"};
        if (std::filesystem::exists(dir.file("out.png"))) {  // finished before the signal: the whole result
            expected.push_back("out.png");
            EXPECT_EQ(read_bytes(dir.file("out.png")), complete);
        }
        EXPECT_EQ(dir.entries(), expected);
    }
    EXPECT_GT(interrupted, 0);
}

// A Latin-1 file name is not UTF-8: the "image" member says U+FFFD for each
// such byte, so every line stays one valid JSON value.
TEST(CliJson, NonUtf8PathGivesValidJson) {
    TempDir dir;
    const std::string path = dir.file("caf\xe9-\xff.npy");
    io::write_image(path, convert<float>(structured_image(8, 8, 1, 3)));
    CliResult r = run_cli({"metrics", "--backend", "cpu", path});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(valid_utf8(r.out)) << r.out;
    const json::Value line = json::parse(r.out, "stdout");
    const json::Value* image = line.find("image");
    ASSERT_TRUE(image && image->is_string());
    EXPECT_EQ(image->string(), dir.file("caf\xef\xbf\xbd-\xef\xbf\xbd.npy"));
}

}  // namespace
}  // namespace vkfuse::test

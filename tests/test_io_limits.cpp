// What a file may not make the readers and writers do (issue 11): a header
// never makes a reader read or allocate more than it promises, a huge sparse
// file is refused (or read only as far as its header says) at once, an output
// follows the umask or keeps the mode of the file it replaces, any name the
// file system accepts can be written, a device is written in place, and JSON
// strings stay valid UTF-8 whatever bytes a name holds. Only the public I/O
// API and json::quote: these tests build against the code before the fix too.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "expect_error.hpp"
#include "io/json_value.hpp"
#include "io_test_files.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

TEST(ReadLimits, TerabyteSparseNpyIsRefusedWithoutReadingIt) {
    TempDir dir;
    const std::string path = dir.file("huge.npy");
    write_sparse(path, npy_header_only(16, 16, 3), kTerabyte);
    const auto start = Clock::now();
    expect_read_error(path, ErrorKind::Format, "corrupt: header says 16x16x3 float32 (3072 bytes) but the file has");
    EXPECT_LT(seconds_since(start), 1.0);
}

TEST(ReadLimits, TerabyteSparseFileOfZerosIsNotAPng) {
    TempDir dir;
    const std::string path = dir.file("zeros.png");
    write_sparse(path, "", kTerabyte);
    const auto start = Clock::now();
    expect_read_error(path, ErrorKind::Format, "not a PNG file");
    EXPECT_LT(seconds_since(start), 1.0);
}

// PNG has no size field: the reader stops at IEND and never looks further.
TEST(ReadLimits, PngIsReadOnlyUpToIendOfATerabyteFile) {
    TempDir dir;
    const std::string path = dir.file("tail.png");
    write_sparse(path, zero_png(64, 48), kTerabyte);
    const auto start = Clock::now();
    Image image = io::read_image(path);
    EXPECT_LT(seconds_since(start), 1.0);
    EXPECT_EQ(image.height, 48);
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.channels, 1);
}

// A chunk claiming 2 GiB in a sparse file: refused, not followed to its end.
TEST(ReadLimits, HugeChunkInASparsePngIsNotFollowed) {
    TempDir dir;
    const std::string path = dir.file("chunk.png");
    write_sparse(path, png_signature() + ihdr(64, 48) + be32(0x7fffffff) + "vkFz", kTerabyte);
    const auto start = Clock::now();
    expect_read_error(path, ErrorKind::Format, "corrupt PNG");
    EXPECT_LT(seconds_since(start), 1.0);
}

TEST(WriteModes, NewFileFollowsTheUmask) {
    TempDir dir;
    {
        Umask mask(077);
        io::write_image(dir.file("private.npy"), Image(2, 3, 1));
        io::write_image(dir.file("private.png"), Image(2, 3, 1));
    }
    {
        Umask mask(027);
        io::write_image(dir.file("group.npy"), Image(2, 3, 1));
    }
    {
        Umask mask(002);
        io::write_image(dir.file("shared.npy"), Image(2, 3, 1));
    }
    EXPECT_EQ(mode_of(dir.file("private.npy")), 0600u);
    EXPECT_EQ(mode_of(dir.file("private.png")), 0600u);
    EXPECT_EQ(mode_of(dir.file("group.npy")), 0640u);
    EXPECT_EQ(mode_of(dir.file("shared.npy")), 0664u);
}

TEST(WriteModes, ReplacedFileKeepsItsMode) {
    TempDir dir;
    Umask mask(022);
    for (unsigned mode : {0600u, 0640u, 0604u, 0444u}) {
        SCOPED_TRACE(mode);
        const std::string path = dir.file("kept.npy");
        std::filesystem::remove(path);
        write_bytes(path, "the previous result");
        ASSERT_EQ(::chmod(path.c_str(), mode), 0);
        io::write_image(path, Image(2, 3, 3));
        EXPECT_EQ(mode_of(path), mode);
        EXPECT_EQ(io::read_image(path).height, 2);
    }
}

// Only root may give a file away: there, a replaced file keeps its owner.
TEST(WriteModes, ReplacedFileKeepsItsOwnerWhereAllowed) {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to create a file owned by someone else";
    TempDir dir;
    const std::string path = dir.file("owned.npy");
    write_bytes(path, "x");
    ASSERT_EQ(::chown(path.c_str(), 4321, 8765), 0);
    ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
    io::write_image(path, Image(2, 2, 1));
    struct stat st {};
    ASSERT_EQ(::stat(path.c_str(), &st), 0);
    EXPECT_EQ(st.st_uid, 4321u);
    EXPECT_EQ(st.st_gid, 8765u);
    EXPECT_EQ(st.st_mode & 07777, 0640u);
}

// The temporary's name must not grow with the output's: 255 bytes is NAME_MAX.
TEST(WriteNames, EveryLengthUpToNameMaxWorks) {
    TempDir dir;
    for (std::size_t length : {240u, 244u, 250u, 255u}) {
        SCOPED_TRACE(length);
        const std::string name = std::string(length - 4, 'n') + ".npy";
        io::write_image(dir.file(name), Image(2, 2, 1));
        EXPECT_EQ(io::read_image(dir.file(name)).width, 2);
        std::filesystem::remove(dir.file(name));
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(WriteNames, DotsInsideANameAreJustCharacters) {
    TempDir dir;
    io::write_image(dir.file("000040..png"), Image(2, 2, 1));
    io::write_image(dir.file("..a.npy"), Image(2, 2, 1));
    EXPECT_EQ(io::read_image(dir.file("000040..png")).height, 2);
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"..a.npy", "000040..png"}));
}

// A device or FIFO is written in place: /dev/full reports the full disk, and
// the name that led there (a symbolic link here) is left as it was.
TEST(WriteDevices, DevFullIsAWriteErrorAndStaysADevice) {
    TempDir dir;
    const std::string link = dir.file("full.npy");
    std::filesystem::create_symlink("/dev/full", link);
    expect_error([&] { io::write_image(link, Image(4, 4, 3)); }, link, ErrorKind::Io, "No space left on device");
    EXPECT_TRUE(std::filesystem::is_symlink(link));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"full.npy"});
    struct stat st {};
    ASSERT_EQ(::stat("/dev/full", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(WriteDevices, DevNullTakesTheImage) {
    TempDir dir;
    const std::string link = dir.file("null.png");
    std::filesystem::create_symlink("/dev/null", link);
    io::write_image(link, Image(4, 4, 3));
    EXPECT_TRUE(std::filesystem::is_symlink(link));
}

// ulimit -f with SIGXFSZ ignored: the kernel's own "disk full" for one
// process. The write fails, the error names the file, nothing is left.
TEST(WriteDevices, FileSizeLimitIsAnErrorAndLeavesNothing) {
    TempDir dir;
    const std::string path = dir.file("big.npy");
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        ::signal(SIGXFSZ, SIG_IGN);
        struct rlimit lim {64 * 1024, 64 * 1024};
        ::setrlimit(RLIMIT_FSIZE, &lim);
        try {
            io::write_image(path, Image(128, 128, 3));
        } catch (const Error& e) {
            const std::string what = e.what();
            ::_exit(what.rfind(path + ": ", 0) == 0 && what.find("File too large") != std::string::npos ? 3 : 4);
        }
        ::_exit(5);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 3) << "3: Error naming the file, 4: another message, 5: no error";
    EXPECT_TRUE(dir.entries().empty());
}

TEST(JsonQuote, InvalidUtf8BecomesReplacementCharacters) {
    // Latin-1 'e acute', a lone continuation byte, a surrogate (ED A0 80), an
    // overlong '/' (C0 AF), a cut-off euro sign, and bytes never valid.
    const std::string bad = "caf\xe9 \x80 \xed\xa0\x80 \xc0\xaf \xe2\x82 \xff\xfe";
    const std::string quoted = json::quote(bad);
    EXPECT_TRUE(valid_utf8(quoted)) << quoted;
    EXPECT_EQ(quoted, "\"caf\\ufffd \\ufffd \\ufffd\\ufffd\\ufffd \\ufffd\\ufffd \\ufffd\\ufffd \\ufffd\\ufffd\"");
    const json::Value back = json::parse(quoted, "test");
    ASSERT_TRUE(back.is_string());
    EXPECT_TRUE(valid_utf8(back.string()));
}

TEST(JsonQuote, WellFormedUtf8PassesThrough) {
    const std::string good = "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80 \xef\xbf\xbf \xf4\x8f\xbf\xbf";
    EXPECT_EQ(json::quote(good), "\"" + good + "\"");
    EXPECT_EQ(json::quote(std::string("a\"\\\n\x01", 5)), "\"a\\\"\\\\\\u000a\\u0001\"");
    // Through the writer too: an object key and a string value.
    json::Value::Object o;
    o.emplace_back(std::string("k\xff", 2), json::Value(std::string("v\xc3", 2)));
    EXPECT_EQ(json::write(json::Value(std::move(o))), "{\"k\\ufffd\": \"v\\ufffd\"}\n");
}

}  // namespace
}  // namespace vkfuse::test

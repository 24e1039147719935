// io::write_atomically's staging (an unnamed O_TMPFILE file, or a short
// hidden name where the file system has none), the signal handler that
// removes named temporaries, header-only reads, and the memory figures the
// CLI plans with.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

#include "expect_error.hpp"
#include "io/atomic_write.hpp"
#include "io/image_header.hpp"
#include "io/interrupt_cleanup.hpp"
#include "io/memory_available.hpp"
#include "io_test_files.hpp"
#include "temp_dir.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

using io::Staging;

void write_text(const std::string& path, const std::string& text, Staging staging) {
    io::write_atomically(path, [&](std::FILE* out) { io::write_all(out, text, path); }, staging);
}

// What the directory holds while the body is being written.
std::vector<std::string> entries_while_writing(const TempDir& dir, Staging staging) {
    std::vector<std::string> seen;
    io::write_atomically(dir.file("out.txt"), [&](std::FILE* out) {
        io::write_all(out, std::string("body"), "out.txt");
        seen = dir.entries();
    }, staging);
    return seen;
}

TEST(AtomicStaging, NamedStagingUsesAShortHiddenName) {
    TempDir dir;
    const std::vector<std::string> seen = entries_while_writing(dir, Staging::Named);
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].size(), 16u);
    EXPECT_EQ(seen[0].rfind(".vkfuse-", 0), 0u);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
    EXPECT_EQ(read_bytes(dir.file("out.txt")), "body");
}

// Where O_TMPFILE works (ext4, tmpfs, xfs, btrfs) the body has no name at all
// until it is complete; elsewhere the named fallback is taken.
TEST(AtomicStaging, AutoStagingHasNoNameWhileWriting) {
    TempDir dir;
    const std::vector<std::string> seen = entries_while_writing(dir, Staging::Auto);
    if (!seen.empty()) GTEST_SKIP() << "no O_TMPFILE on this file system: staged as " << seen[0];
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(AtomicStaging, BothStagingsFollowTheUmaskAndKeepModes) {
    for (Staging staging : {Staging::Auto, Staging::Named}) {
        TempDir dir;
        const mode_t old = ::umask(077);
        write_text(dir.file("new"), "a", staging);
        ::umask(022);
        write_text(dir.file("kept"), "a", staging);
        ::chmod(dir.file("kept").c_str(), 0600);
        write_text(dir.file("kept"), "b", staging);
        ::umask(old);
        EXPECT_EQ(mode_of(dir.file("new")), 0600u);
        EXPECT_EQ(mode_of(dir.file("kept")), 0600u);
        EXPECT_EQ(read_bytes(dir.file("kept")), "b");
    }
}

TEST(AtomicStaging, AThrowingBodyLeavesTheOldFileAndNoTemporary) {
    for (Staging staging : {Staging::Auto, Staging::Named}) {
        TempDir dir;
        write_bytes(dir.file("out.txt"), "old");
        EXPECT_THROW(io::write_atomically(dir.file("out.txt"), [&](std::FILE* out) {
            io::write_all(out, std::string("new, half"), "out.txt");
            throw std::runtime_error("stop");
        }, staging),
                     std::runtime_error);
        EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
        EXPECT_EQ(read_bytes(dir.file("out.txt")), "old");
    }
}

// A body that ignores fwrite's result still cannot make a short file look
// complete: the stream's error flag is checked before the rename.
TEST(AtomicStaging, UnreportedStreamErrorsAreCaught) {
    TempDir dir;
    const std::string link = dir.file("full.json");
    std::filesystem::create_symlink("/dev/full", link);
    expect_error([&] {
        io::write_atomically(link, [](std::FILE* out) { std::fwrite("x", 1, 1, out); });
    }, link, ErrorKind::Io, "No space left on device");
    expect_error([&] { write_text(link, std::string(100000, 'x'), Staging::Auto); }, link, ErrorKind::Io,
                 "cannot write: No space left on device");
}

TEST(AtomicStaging, DirectoriesAreNotReplaced) {
    TempDir dir;
    std::filesystem::create_directory(dir.file("folder"));
    expect_error([&] { write_text(dir.file("folder"), "x", Staging::Auto); }, dir.file("folder"), ErrorKind::Io,
                 "cannot replace: Is a directory");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"folder"});
}

// The handler, in a child: a SIGTERM in the middle of a named write removes
// the temporary and the process still dies of SIGTERM.
TEST(InterruptCleanup, SigtermDuringANamedWriteLeavesNothing) {
    for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
        SCOPED_TRACE(sig);
        TempDir dir;
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            io::install_interrupt_cleanup();
            io::write_atomically(dir.file("out.npy"), [&](std::FILE* out) {
                io::write_all(out, std::string(1000, 'x'), "out.npy");
                std::fflush(out);
                ::raise(sig);
            }, Staging::Named);
            ::_exit(0);  // not reached: the signal ends the child
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
        EXPECT_TRUE(dir.entries().empty());
    }
}

// An unnamed staging file needs no handler: it vanishes even with SIGKILL.
TEST(InterruptCleanup, SigkillDuringAnUnnamedWriteLeavesNothing) {
    TempDir dir;
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        io::write_atomically(dir.file("out.npy"), [&](std::FILE* out) {
            io::write_all(out, std::string(1000, 'x'), "out.npy");
            std::fflush(out);
            ::raise(SIGKILL);
        });
        ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
    EXPECT_TRUE(dir.entries().empty());
}

// A signal the caller ignores stays ignored (nohup), and a handler someone
// else installed (vkfuse run's StopSignal) is not replaced.
TEST(InterruptCleanup, IgnoredSignalsAndOtherHandlersAreLeftAlone) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        static volatile sig_atomic_t seen = 0;
        ::signal(SIGTERM, SIG_IGN);
        ::signal(SIGINT, [](int) { seen = 1; });
        io::install_interrupt_cleanup();
        ::raise(SIGTERM);
        ::raise(SIGINT);
        ::_exit(seen == 1 ? 7 : 8);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 7);
}

TEST(ImageHeader, ReadsShapeWithoutDecoding) {
    TempDir dir;
    io::write_image(dir.file("a.npy"), Image(5, 7, 3));
    io::write_image(dir.file("a.png"), Image(6, 4, 1));
    const io::ImageHeader npy = io::read_image_header(dir.file("a.npy"));
    EXPECT_EQ(npy.height, 5);
    EXPECT_EQ(npy.width, 7);
    EXPECT_EQ(npy.channels, 3);
    EXPECT_EQ(npy.image_bytes(), 5u * 7 * 3 * 4);
    const io::ImageHeader png = io::read_image_header(dir.file("a.png"));
    EXPECT_EQ(png.height, 6);
    EXPECT_EQ(png.width, 4);
    EXPECT_EQ(png.channels, 1);
    // 16384 x 16384 in 270 kB of undecodable data: the header alone is read.
    write_bytes(dir.file("huge.png"), fake_huge_png(16384, 270000));
    const io::ImageHeader huge = io::read_image_header(dir.file("huge.png"));
    EXPECT_EQ(huge.height, 16384);
    EXPECT_EQ(huge.image_bytes(), std::uint64_t(1) << 30);
    EXPECT_LT(huge.decode_bytes, std::uint64_t(1) << 20);  // one row and a read buffer
    write_sparse(dir.file("sparse.npy"), npy_header_only(4, 4, 1), kTerabyte);
    expect_error([&] { io::read_image_header(dir.file("sparse.npy")); }, dir.file("sparse.npy"), ErrorKind::Format,
                 "corrupt: header says 4x4x1");
}

TEST(MemoryAvailable, ByteCountsAndTheirText) {
    EXPECT_EQ(io::parse_byte_count("1073741824"), std::uint64_t(1) << 30);
    EXPECT_EQ(io::parse_byte_count("4G"), std::uint64_t(4) << 30);
    EXPECT_EQ(io::parse_byte_count("512mib"), std::uint64_t(512) << 20);
    EXPECT_EQ(io::parse_byte_count("2TB"), std::uint64_t(2) << 40);
    EXPECT_EQ(io::parse_byte_count("100b"), 100u);
    EXPECT_FALSE(io::parse_byte_count(""));
    EXPECT_FALSE(io::parse_byte_count("G"));
    EXPECT_FALSE(io::parse_byte_count("4x"));
    EXPECT_FALSE(io::parse_byte_count("-1"));
    EXPECT_FALSE(io::parse_byte_count("99999999999999999999"));
    EXPECT_FALSE(io::parse_byte_count("99999999999T"));
    EXPECT_EQ(io::memory_text(16.0 * (1 << 30)), "16.0 GiB");
    EXPECT_EQ(io::memory_text(512.0 * (1 << 20)), "512 MiB");
    EXPECT_EQ(io::memory_text(100), "100 bytes");
}

TEST(MemoryAvailable, TheEnvironmentLowersTheFigure) {
    ::setenv("VKFUSE_MEMORY_LIMIT", "3M", 1);
    const auto low = io::available_memory();
    ::setenv("VKFUSE_MEMORY_LIMIT", "many", 1);
    EXPECT_THROW(io::available_memory(), Error);
    ::unsetenv("VKFUSE_MEMORY_LIMIT");
    ASSERT_TRUE(low);
    EXPECT_EQ(low->bytes, std::uint64_t(3) << 20);
    EXPECT_EQ(low->source, "VKFUSE_MEMORY_LIMIT");
    const auto real = io::available_memory();
    ASSERT_TRUE(real);  // /proc/meminfo at least
    EXPECT_GT(real->bytes, std::uint64_t(3) << 20);
}

}  // namespace
}  // namespace vkfuse::test

// io::write_atomically (src/io/atomic_write.hpp): the whole file or nothing.
// Only the header's contract is tested here, not how the temporary is made or
// named: a write_body that fails part-way leaves the destination byte for byte
// as it was and the directory as it was; while the body writes, the
// destination still holds its old content; success replaces it whole.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/atomic_write.hpp"
#include "temp_dir.hpp"

namespace vkfuse::test {
namespace {

// Bytes that no prefix of another such string matches by accident.
std::string pattern(std::size_t n, unsigned seed) {
    std::string s(n, '\0');
    unsigned x = seed * 2654435761u + 1;
    for (char& c : s) {
        x = x * 1103515245u + 12345u;
        c = char(x >> 23);
    }
    return s;
}

// Byte-for-byte equality, reported by size and first difference (not by
// printing tens of kilobytes).
::testing::AssertionResult same_bytes(const std::string& got, const std::string& want) {
    if (got == want) return ::testing::AssertionSuccess();
    std::size_t at = 0;
    while (at < got.size() && at < want.size() && got[at] == want[at]) ++at;
    return ::testing::AssertionFailure() << got.size() << " bytes where " << want.size()
                                         << " were expected, first difference at byte " << at;
}

void put(std::FILE* f, const std::string& bytes) {
    ASSERT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
}

struct BodyFailed : std::runtime_error {
    BodyFailed() : std::runtime_error("body failed part-way") {}
};

// More than any stdio buffer, flushed: the bytes really reached a file before
// the body throws.
TEST(AtomicWrite, BodyThatThrowsPartWayLeavesTheOldFileAndNothingElse) {
    TempDir dir;
    const std::string path = dir.file("image.npy");
    const std::string old = pattern(70000, 1);
    write_bytes(path, old);
    write_bytes(dir.file("neighbour.txt"), "x");
    const std::vector<std::string> before = dir.entries();
    EXPECT_THROW(io::write_atomically(path,
                                      [&](std::FILE* f) {
                                          put(f, pattern(200000, 2));
                                          std::fflush(f);
                                          throw BodyFailed();
                                      }),
                 BodyFailed);
    EXPECT_TRUE(same_bytes(read_bytes(path), old));
    EXPECT_EQ(dir.entries(), before);
}

// Without an old file, a failure leaves no file at all.
TEST(AtomicWrite, BodyThatThrowsCreatesNothing) {
    TempDir dir;
    const std::string path = dir.file("new.png");
    try {
        io::write_atomically(path, [&](std::FILE* f) {
            put(f, pattern(5000, 3));
            std::fflush(f);
            throw BodyFailed();
        });
        ADD_FAILURE() << "the body's exception did not propagate";
    } catch (const BodyFailed& e) {
        EXPECT_STREQ(e.what(), "body failed part-way");  // the body's own exception, unchanged
    }
    EXPECT_TRUE(dir.entries().empty());
}

// Anyone reading the destination while the new content is written sees the
// old file whole; afterwards, the new file whole (shorter than the old one:
// nothing of the old is left at its end).
TEST(AtomicWrite, DestinationKeepsItsOldContentWhileTheBodyWrites) {
    TempDir dir;
    const std::string path = dir.file("out.npy");
    const std::string old = pattern(90000, 4), fresh = pattern(30000, 5);
    write_bytes(path, old);
    int checks = 0;
    io::write_atomically(path, [&](std::FILE* f) {
        EXPECT_TRUE(same_bytes(read_bytes(path), old)) << "before the body writes";
        put(f, fresh.substr(0, 20000));
        std::fflush(f);
        EXPECT_TRUE(same_bytes(read_bytes(path), old)) << "after part of the new content";
        put(f, fresh.substr(20000));
        std::fflush(f);
        EXPECT_TRUE(same_bytes(read_bytes(path), old)) << "after all of the new content, before returning";
        ++checks;
    });
    EXPECT_EQ(checks, 1);
    EXPECT_TRUE(same_bytes(read_bytes(path), fresh));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.npy"});
}

// A new file does not appear under its name before it is complete.
TEST(AtomicWrite, NewFileAppearsOnlyWhenComplete) {
    TempDir dir;
    const std::string path = dir.file("fresh.npy");
    const std::string fresh = pattern(40000, 6);
    io::write_atomically(path, [&](std::FILE* f) {
        put(f, fresh);
        std::fflush(f);
        EXPECT_FALSE(std::filesystem::exists(path)) << "visible before the body returned";
    });
    EXPECT_TRUE(same_bytes(read_bytes(path), fresh));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"fresh.npy"});
}

// A failure after a successful write (the second body throws) keeps the first
// write's content, and several failures in a row leave nothing behind.
TEST(AtomicWrite, RepeatedFailuresKeepTheLastGoodWrite) {
    TempDir dir;
    const std::string path = dir.file("log.json");
    const std::string good = pattern(12345, 7);
    io::write_atomically(path, [&](std::FILE* f) { put(f, good); });
    for (int i = 0; i < 5; ++i)
        EXPECT_THROW(io::write_atomically(path,
                                          [&](std::FILE* f) {
                                              put(f, pattern(std::size_t(1000 + i * 20000), unsigned(8 + i)));
                                              throw BodyFailed();  // not flushed: buffered bytes too
                                          }),
                     BodyFailed);
    EXPECT_TRUE(same_bytes(read_bytes(path), good));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"log.json"});
}

}  // namespace
}  // namespace vkfuse::test

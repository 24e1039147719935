// MCAP files as io::mcap::Writer writes them, walked record by record here
// against the specification's rules (the offsets and CRCs a seeking reader
// relies on); tests/mcap/check_mcap.sh has the MCAP project's own reader
// read the same sample.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "io/mcap_writer.hpp"
#include "mcap/mcap_sample.hpp"
#include "temp_dir.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::test {
namespace {

using Bytes = std::vector<std::uint8_t>;

struct Cursor {
    const Bytes& b;
    std::size_t at;
    template <class T>
    T num() {
        T v = 0;
        for (std::size_t i = 0; i < sizeof(T); ++i) v |= T(T(b.at(at + i)) << (8 * i));
        at += sizeof(T);
        return v;
    }
    std::string str() {
        const std::uint32_t n = num<std::uint32_t>();
        std::string s(reinterpret_cast<const char*>(&b.at(at)), n);
        at += n;
        return s;
    }
};

struct Record {
    std::uint8_t op;
    std::size_t start, content, end;  // offsets: the opcode, the content, past the record
};

std::vector<Record> records(const Bytes& b, std::size_t from, std::size_t to) {
    std::vector<Record> out;
    for (std::size_t at = from; at < to;) {
        Cursor c{b, at + 1};
        const std::uint64_t length = c.num<std::uint64_t>();
        out.push_back({b.at(at), at, at + 9, at + 9 + length});
        at = out.back().end;
    }
    return out;
}

Bytes write_sample_file(const TempDir& tmp, std::size_t chunk_bytes) {
    const std::string path = tmp.file("s.mcap");
    std::FILE* f = std::fopen(path.c_str(), "wb");
    io::mcap::Writer w(f, path, {"ros2", "vkfuse tests", chunk_bytes, io::mcap::Compression::None});
    write_sample(w);
    std::fclose(f);
    f = std::fopen(path.c_str(), "rb");
    Bytes b;
    for (int c; (c = std::fgetc(f)) != EOF;) b.push_back(std::uint8_t(c));
    std::fclose(f);
    return b;
}

TEST(Mcap, Crc32IsZlibs) {
    const std::string text = "123456789";
    EXPECT_EQ(io::mcap::crc32({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}), 0xCBF43926u);
    const auto* p = reinterpret_cast<const std::uint8_t*>(text.data());
    EXPECT_EQ(io::mcap::crc32({p + 4, 5}, io::mcap::crc32({p, 4})), 0xCBF43926u);  // continued
}

TEST(Mcap, OffsetsIndexesAndCrcsHoldInOneChunkAndInMany) {
    TempDir tmp;
    for (const std::size_t chunk_bytes : {std::size_t(1) << 20, std::size_t(2048)}) {
        SCOPED_TRACE(chunk_bytes);
        const Bytes b = write_sample_file(tmp, chunk_bytes);
        const Bytes magic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
        ASSERT_GT(b.size(), 2 * magic.size() + 29);
        EXPECT_TRUE(std::equal(magic.begin(), magic.end(), b.begin()));
        EXPECT_TRUE(std::equal(magic.begin(), magic.end(), b.end() - 8));
        // The footer: 1 + 8 + 20 bytes before the closing magic.
        Cursor footer{b, b.size() - 8 - 29};
        ASSERT_EQ(footer.num<std::uint8_t>(), 0x02);
        ASSERT_EQ(footer.num<std::uint64_t>(), 20u);
        const std::uint64_t summary_start = footer.num<std::uint64_t>();
        const std::uint64_t offsets_start = footer.num<std::uint64_t>();
        const std::uint32_t summary_crc = footer.num<std::uint32_t>();
        EXPECT_EQ(io::mcap::crc32({b.data() + summary_start, b.size() - 8 - 4 - summary_start}), summary_crc);
        // Data End sits just before the summary, with the CRC of everything before it.
        const std::vector<Record> data = records(b, 8, summary_start);
        ASSERT_EQ(data.back().op, 0x0F);
        Cursor data_end{b, data.back().content};
        EXPECT_EQ(data_end.num<std::uint32_t>(), io::mcap::crc32({b.data(), data.back().start}));
        // Every chunk's CRC, and every message index entry points at a message of its time.
        std::map<std::size_t, Record> chunks;
        std::size_t messages = 0;
        for (std::size_t i = 0; i < data.size(); ++i) {
            const Record& r = data[i];
            if (r.op != 0x06) continue;
            chunks[r.start] = r;
            Cursor c{b, r.content};
            c.num<std::uint64_t>(), c.num<std::uint64_t>();
            const std::uint64_t size = c.num<std::uint64_t>();
            const std::uint32_t crc = c.num<std::uint32_t>();
            EXPECT_EQ(c.str(), "");
            ASSERT_EQ(c.num<std::uint64_t>(), size);
            const std::size_t inner = c.at;
            EXPECT_EQ(io::mcap::crc32({b.data() + inner, size}), crc);
            for (std::size_t j = i + 1; j < data.size() && data[j].op == 0x07; ++j) {
                Cursor m{b, data[j].content};
                const auto channel = m.num<std::uint16_t>();
                const std::size_t end = m.at + 4 + m.num<std::uint32_t>();
                while (m.at < end) {
                    const std::uint64_t time = m.num<std::uint64_t>(), offset = m.num<std::uint64_t>();
                    Cursor msg{b, inner + offset};
                    ASSERT_EQ(msg.num<std::uint8_t>(), 0x05);
                    msg.num<std::uint64_t>();
                    EXPECT_EQ(msg.num<std::uint16_t>(), channel);
                    msg.num<std::uint32_t>();
                    EXPECT_EQ(msg.num<std::uint64_t>(), time);
                    ++messages;
                }
            }
        }
        EXPECT_EQ(messages, sample_messages().size());
        EXPECT_EQ(chunk_bytes > 100000 ? std::size_t(1) : std::size_t(2), std::min<std::size_t>(chunks.size(), 2));
        // The summary: schemas, channels, statistics, chunk indexes pointing at the chunks; its offsets.
        std::map<std::uint8_t, int> seen;
        for (const Record& r : records(b, summary_start, offsets_start)) {
            ++seen[r.op];
            if (r.op == 0x08) {
                Cursor c{b, r.content};
                c.num<std::uint64_t>(), c.num<std::uint64_t>();
                const std::uint64_t at = c.num<std::uint64_t>(), length = c.num<std::uint64_t>();
                ASSERT_TRUE(chunks.count(at));
                EXPECT_EQ(chunks[at].end - chunks[at].start, length);
            }
            if (r.op == 0x0B) {
                Cursor statistics{b, r.content};
                EXPECT_EQ(statistics.num<std::uint64_t>(), sample_messages().size());
            }
        }
        EXPECT_EQ(seen[0x03], 2);
        EXPECT_EQ(seen[0x04], 3);
        EXPECT_EQ(seen[0x0B], 1);
        EXPECT_EQ(std::size_t(seen[0x08]), chunks.size());
        for (const Record& r : records(b, offsets_start, b.size() - 8 - 29)) {
            ASSERT_EQ(r.op, 0x0E);
            Cursor c{b, r.content};
            const std::uint8_t group = c.num<std::uint8_t>();
            const std::uint64_t start = c.num<std::uint64_t>();
            EXPECT_EQ(b.at(start), group);
        }
    }
}

TEST(Mcap, AFailedWriteNamesTheFile) {
    std::FILE* full = std::fopen("/dev/full", "wb");
    if (!full) GTEST_SKIP() << "no /dev/full";
    std::setvbuf(full, nullptr, _IONBF, 0);
    expect_error([&] {
        io::mcap::Writer w(full, "rig.mcap");
        write_sample(w);
    }, "rig.mcap", ErrorKind::Io, "write failed");
    std::fclose(full);
}

TEST(Mcap, MessagesOnUnknownChannelsAreRefused) {
    TempDir tmp;
    const std::string path = tmp.file("x.mcap");
    std::FILE* f = std::fopen(path.c_str(), "wb");
    io::mcap::Writer w(f, path);
    expect_error([&] { w.write(1, 0, 0, 0, {}); }, path, ErrorKind::InvalidArgument, "channel 1 was not added");
    expect_error([&] { w.add_channel(3, "/t", "json"); }, path, ErrorKind::InvalidArgument,
                 "names schema 3, which was not added");
    w.finish();
    std::fclose(f);
}

}  // namespace
}  // namespace vkfuse::test

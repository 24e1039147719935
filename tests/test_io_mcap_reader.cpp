// io::mcap::Reader on files io::mcap::Writer wrote (every compression), and
// on the same files cut short, with bytes flipped, and with records crafted
// to lie about their sizes: the messages before the damage come back, the
// reader says where it stopped, and nothing crashes or allocates what a
// length claims.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "io/mcap_compression.hpp"
#include "io/mcap_reader.hpp"
#include "io/mcap_records.hpp"
#include "io/mcap_writer.hpp"
#include "mcap/mcap_sample.hpp"
#include "temp_dir.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::test {
namespace {

using io::mcap::Compression;

std::string write_sample_file(const TempDir& tmp, Compression c, std::size_t chunk_bytes) {
    const std::string path = tmp.file("s.mcap");
    std::FILE* f = std::fopen(path.c_str(), "wb");
    io::mcap::Writer w(f, path, {"ros2", "vkfuse tests", chunk_bytes, c});
    write_sample(w);
    std::fclose(f);
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string save(const TempDir& tmp, const std::string& name, const std::string& bytes) {
    const std::string path = tmp.file(name);
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

struct Scan {
    std::vector<io::mcap::MessageLocation> at;
    std::string lines;  // as sample_lines() writes them
    std::string stopped;
};

Scan scan(io::mcap::Reader& r) {
    Scan s;
    io::mcap::Reader::Visitor v;
    v.message = [&](const io::mcap::Message& m) {
        std::uint32_t sum = 0;
        for (char c : m.data) sum += std::uint8_t(c);
        s.lines += r.channel(m.channel)->topic + " " + std::to_string(m.sequence) + " " + std::to_string(m.log_time) +
                   " " + std::to_string(m.publish_time) + " " + std::to_string(m.data.size()) + " " +
                   std::to_string(sum) + "\n";
        s.at.push_back(m.at);
    };
    s.stopped = r.scan(v);
    return s;
}

TEST(McapReader, ReadsBackEveryCompression) {
    for (Compression c : {Compression::None, Compression::Zstd, Compression::Lz4})
        for (std::size_t chunk : {std::size_t(2048), std::size_t(1) << 20}) {
            SCOPED_TRACE(std::string(io::mcap::option_name(c)) + " chunk " + std::to_string(chunk));
            TempDir tmp;
            write_sample_file(tmp, c, chunk);
            io::mcap::Reader r(tmp.file("s.mcap"));
            EXPECT_EQ(r.profile(), "ros2");
            const Scan s = scan(r);
            EXPECT_EQ(s.stopped, "");
            EXPECT_EQ(s.lines, sample_lines());
            // Read again by location, in reverse so the chunk cache is no help.
            const auto want = sample_messages();
            for (std::size_t i = want.size(); i-- > 0;) {
                const io::mcap::Message m = r.read(s.at[i]);
                ASSERT_EQ(std::string(m.data), std::string(want[i].data.begin(), want[i].data.end())) << i;
                EXPECT_EQ(m.log_time, want[i].log_time);
            }
        }
}

// The sample's lines, made once: the tests below compare thousands of reads with them.
const std::string& all_sample_lines() {
    static const std::string all = sample_lines();
    return all;
}

// The lines of the first n sample messages.
std::string first_lines(std::size_t n) {
    const std::string& all = all_sample_lines();
    std::size_t at = 0;
    for (std::size_t i = 0; i < n; ++i) at = all.find('\n', at) + 1;
    return all.substr(0, at);
}

TEST(McapReader, AFileCutAnywhereGivesTheMessagesBeforeTheCut) {
    TempDir tmp;
    const std::string whole = write_sample_file(tmp, Compression::Zstd, 2048);
    std::size_t refused = 0, partial = 0;
    for (std::size_t cut = 0; cut < whole.size(); cut += 61) {
        const std::string path = save(tmp, "cut.mcap", whole.substr(0, cut));
        try {
            io::mcap::Reader r(path);
            const Scan s = scan(r);
            // A cut after Data End takes only the summary: every message is there.
            if (s.stopped.empty()) {
                EXPECT_EQ(s.lines, all_sample_lines()) << cut;
            }
            EXPECT_EQ(s.lines, first_lines(s.at.size())) << cut;
            ++partial;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Format) << e.what();
            EXPECT_NE(std::string(e.what()).find("not an MCAP file"), std::string::npos) << e.what();
            EXPECT_LT(cut, 64u);  // only a cut within the magic and the Header
            ++refused;
        }
    }
    EXPECT_GT(partial, 10u);
}

TEST(McapReader, AFlippedByteStopsTheReadingWhereItLies) {
    TempDir tmp;
    const std::string whole = write_sample_file(tmp, Compression::Lz4, 2048);
    for (std::size_t at = 17; at < whole.size(); at += 53) {
        std::string bad = whole;
        bad[at] = char(bad[at] ^ 0x5A);
        const std::string path = save(tmp, "bad.mcap", bad);
        std::unique_ptr<io::mcap::Reader> r;
        try {
            r = std::make_unique<io::mcap::Reader>(path);
        } catch (const Error& e) {
            EXPECT_LT(at, 64u) << e.what();  // the magic or the Header
            continue;
        }
        const Scan s = scan(*r);
        // Never a message that differs from what was written: a chunk's CRC
        // (or its framing) stops the reading before its messages. A record
        // whose opcode turned into an unknown one is skipped, as the
        // specification asks; the data section's CRC then says so at the end.
        if (s.stopped.empty()) {
            EXPECT_EQ(s.lines, all_sample_lines()) << at;
        } else {
            const std::string& all = all_sample_lines();
            std::size_t from = 0;
            for (std::size_t i = 0, next; i < s.lines.size(); i = next) {
                next = s.lines.find('\n', i) + 1;
                from = all.find(s.lines.substr(i, next - i), from);
                ASSERT_NE(from, std::string::npos) << at << ": a message that was not written";
            }
        }
    }
}

std::string crafted(const std::vector<std::string>& records) {
    std::string f(reinterpret_cast<const char*>(io::mcap::kMagic), io::mcap::kMagicSize);
    io::mcap::Bytes header;
    header.str("ros2").str("crafted");
    f += io::mcap::record(io::mcap::kHeader, header);
    for (const std::string& r : records) f += r;
    return f;
}

std::string chunk_claiming(std::uint64_t uncompressed, std::string_view compression, std::uint64_t stored) {
    io::mcap::Bytes c;
    c.num(std::uint64_t(0)).num(std::uint64_t(0)).num(uncompressed).num(std::uint32_t(0)).str(compression);
    c.num(stored).raw(std::string_view("abcd"));
    return io::mcap::record(io::mcap::kChunk, c);
}

TEST(McapReader, LyingRecordsAreRefusedWithWhereAndWhy) {
    TempDir tmp;
    struct Case {
        std::string name, bytes, fragment;
    };
    io::mcap::Bytes huge_head;
    huge_head.num(std::uint8_t(io::mcap::kSchema)).num(std::uint64_t(1) << 40);
    io::mcap::Bytes schema0;
    schema0.num(std::uint16_t(0)).str("x").str("ros2msg").str("");
    io::mcap::Bytes message;
    message.num(std::uint16_t(7)).num(std::uint32_t(0)).num(std::uint64_t(0)).num(std::uint64_t(0));
    io::mcap::Bytes channel;
    channel.num(std::uint16_t(1)).num(std::uint16_t(9)).str("/t").str("cdr").num(std::uint32_t(0));
    io::mcap::Bytes short_string;
    short_string.num(std::uint16_t(1)).num(std::uint32_t(1000)).raw(std::string_view("ab"));
    const Case cases[] = {
        {"2^40-byte record", crafted({huge_head.v}), "Schema: truncated: it claims 1099511627776 bytes"},
        {"2^40-byte chunk", crafted({chunk_claiming(std::uint64_t(1) << 40, "zstd", 4)}),
         "Chunk: it claims 1099511627776 bytes uncompressed, more than"},
        {"records past the chunk", crafted({chunk_claiming(4, "", 1 << 20)}), "Chunk: its records claim 1048576 bytes"},
        {"unknown compression", crafted({chunk_claiming(4, "brotli", 4)}), "compression \"brotli\""},
        {"zstd that is not", crafted({chunk_claiming(4, "zstd", 4)}), "not a zstd frame"},
        {"lz4 that is not", crafted({chunk_claiming(4, "lz4", 4)}), "Chunk: its records: the lz4 frame"},
        {"schema id 0", crafted({io::mcap::record(io::mcap::kSchema, schema0)}), "Schema: schema id 0"},
        {"message on no channel", crafted({io::mcap::record(io::mcap::kMessage, message)}),
         "Message: a message on channel 7, which no Channel record before it declared"},
        {"channel on no schema", crafted({io::mcap::record(io::mcap::kChannel, channel)}), "names schema 9"},
        {"string past its record", crafted({io::mcap::record(io::mcap::kSchema, short_string)}),
         "its fields run past the record"},
        {"no Data End", crafted({}), "the file ends without a Data End record"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        io::mcap::Reader r(save(tmp, "lie.mcap", c.bytes));
        const Scan s = scan(r);
        EXPECT_EQ(s.at.size(), 0u);
        EXPECT_EQ(s.stopped.rfind("byte ", 0), 0u) << s.stopped;
        EXPECT_NE(s.stopped.find(c.fragment), std::string::npos) << s.stopped;
    }
    expect_error([&] { io::mcap::Reader(save(tmp, "png.mcap", "\x89PNG\r\n\x1a\n and more bytes")); },
                 tmp.file("png.mcap"), ErrorKind::Format, "not an MCAP file (no MCAP magic at its start)");
    expect_error([&] { io::mcap::Reader(tmp.file("missing.mcap")); }, tmp.file("missing.mcap"), ErrorKind::Io,
                 "cannot open");
}

TEST(McapCompression, AFrameOfAnotherSizeIsRefused) {
    const std::string data(5000, 'v');
    for (Compression c : {Compression::None, Compression::Zstd, Compression::Lz4}) {
        SCOPED_TRACE(std::string(io::mcap::option_name(c)));
        const std::string packed = io::mcap::compress(c, data);
        EXPECT_EQ(io::mcap::decompress(c, packed, data.size(), "chunk"), data);
        expect_error([&] { io::mcap::decompress(c, packed, data.size() - 1, "chunk"); }, "chunk", ErrorKind::Format, "");
        expect_error([&] { io::mcap::decompress(c, packed, data.size() + 1, "chunk"); }, "chunk", ErrorKind::Format, "");
        if (c != Compression::None)
            expect_error([&] { io::mcap::decompress(c, packed.substr(0, packed.size() / 2), data.size(), "chunk"); },
                         "chunk", ErrorKind::Format, "");
    }
}

}  // namespace
}  // namespace vkfuse::test

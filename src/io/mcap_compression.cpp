// Chunk compression for MCAP through Debian's libzstd and liblz4 (their frame
// formats, which every MCAP reader expects).
#include "io/mcap_compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>

#include "vkfuse/core/error.hpp"

namespace vkfuse::io::mcap {
namespace {

// Fast levels: a recording is written while the rig runs.
constexpr int kZstdLevel = 1;

constexpr struct {
    Compression c;
    std::string_view record, option;
} kNames[] = {{Compression::None, "", "none"}, {Compression::Zstd, "zstd", "zstd"}, {Compression::Lz4, "lz4", "lz4"}};

[[noreturn]] void corrupt(const std::string& what, const std::string& why) {
    throw Error(ErrorKind::Format, what + ": " + why);
}

std::string zstd_decompress(std::string_view data, std::size_t size, const std::string& what) {
    const unsigned long long claimed = ZSTD_getFrameContentSize(data.data(), data.size());
    if (claimed == ZSTD_CONTENTSIZE_ERROR) corrupt(what, "not a zstd frame");
    if (claimed != ZSTD_CONTENTSIZE_UNKNOWN && claimed != size)
        corrupt(what, "the zstd frame holds " + std::to_string(claimed) + " bytes, the chunk says " + std::to_string(size));
    std::string out(size, '\0');
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), data.data(), data.size());
    if (ZSTD_isError(n)) corrupt(what, std::string("zstd: ") + ZSTD_getErrorName(n));
    if (n != size) corrupt(what, "the zstd frame holds " + std::to_string(n) + " bytes, the chunk says " + std::to_string(size));
    return out;
}

std::string lz4_decompress(std::string_view data, std::size_t size, const std::string& what) {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)))
        throw Error(ErrorKind::Io, what + ": lz4: out of memory");
    const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(raw, LZ4F_freeDecompressionContext);
    // One byte more than size: a frame that fills it holds more than it should.
    std::string out(size + 1, '\0');
    std::size_t in_at = 0, out_at = 0;
    for (;;) {
        std::size_t in_n = data.size() - in_at, out_n = out.size() - out_at;
        const std::size_t hint = LZ4F_decompress(ctx.get(), out.data() + out_at, &out_n, data.data() + in_at, &in_n, nullptr);
        if (LZ4F_isError(hint)) corrupt(what, std::string("lz4: ") + LZ4F_getErrorName(hint));
        in_at += in_n;
        out_at += out_n;
        if (out_at > size) corrupt(what, "the lz4 frame holds more than the " + std::to_string(size) + " bytes the chunk says");
        if (hint == 0) break;  // the frame ended
        if (in_n == 0 && out_n == 0) corrupt(what, "the lz4 frame is truncated");
    }
    if (out_at != size)
        corrupt(what, "the lz4 frame holds " + std::to_string(out_at) + " bytes, the chunk says " + std::to_string(size));
    if (in_at != data.size()) corrupt(what, "bytes after the lz4 frame");
    out.resize(size);
    return out;
}

}  // namespace

std::string_view to_string(Compression c) {
    for (const auto& n : kNames)
        if (n.c == c) return n.record;
    return "";
}
std::optional<Compression> parse_compression(std::string_view name) {
    for (const auto& n : kNames)
        if (n.record == name) return n.c;
    return std::nullopt;
}
std::string_view option_name(Compression c) {
    for (const auto& n : kNames)
        if (n.c == c) return n.option;
    return "none";
}
std::optional<Compression> parse_compression_option(std::string_view name) {
    for (const auto& n : kNames)
        if (n.option == name) return n.c;
    return std::nullopt;
}

std::string compress(Compression c, std::string_view data) {
    if (c == Compression::None) return std::string(data);
    if (c == Compression::Zstd) {
        std::string out(ZSTD_compressBound(data.size()), '\0');
        const std::size_t n = ZSTD_compress(out.data(), out.size(), data.data(), data.size(), kZstdLevel);
        if (ZSTD_isError(n)) throw Error(ErrorKind::Io, std::string("zstd: ") + ZSTD_getErrorName(n));
        out.resize(n);
        return out;
    }
    LZ4F_preferences_t prefs{};
    prefs.frameInfo.contentSize = data.size();
    std::string out(LZ4F_compressFrameBound(data.size(), &prefs), '\0');
    const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), &prefs);
    if (LZ4F_isError(n)) throw Error(ErrorKind::Io, std::string("lz4: ") + LZ4F_getErrorName(n));
    out.resize(n);
    return out;
}

std::string decompress(Compression c, std::string_view data, std::size_t size, const std::string& what) {
    if (c == Compression::Zstd) return zstd_decompress(data, size, what);
    if (c == Compression::Lz4) return lz4_decompress(data, size, what);
    if (data.size() != size)
        corrupt(what, "holds " + std::to_string(data.size()) + " bytes, the chunk says " + std::to_string(size));
    return std::string(data);
}

}  // namespace vkfuse::io::mcap

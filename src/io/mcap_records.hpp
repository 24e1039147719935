// io/mcap_records.hpp - the MCAP record layer the writer and the reader
// share (mcap.dev/spec): the magic, the opcodes, and building and reading
// little-endian fields. A record is an opcode byte, a u64 content length and
// its content; a string is a u32 length and its bytes; a map or an array a
// u32 length in bytes and its entries.
#pragma once
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

namespace vkfuse::io::mcap {

inline constexpr std::uint8_t kMagic[] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr std::size_t kMagicSize = sizeof kMagic;
inline constexpr std::size_t kRecordHead = 9;  // opcode and content length

enum Op : std::uint8_t {
    kHeader = 0x01,
    kFooter = 0x02,
    kSchema = 0x03,
    kChannel = 0x04,
    kMessage = 0x05,
    kChunk = 0x06,
    kMessageIndex = 0x07,
    kChunkIndex = 0x08,
    kAttachment = 0x09,
    kAttachmentIndex = 0x0A,
    kStatistics = 0x0B,
    kMetadata = 0x0C,
    kMetadataIndex = 0x0D,
    kSummaryOffset = 0x0E,
    kDataEnd = 0x0F,
};

// The bytes of one record's content, or of a map or array inside one (in a
// std::string: GCC 12 misreads growing a vector of bytes from empty as an
// overflow).
struct Bytes {
    std::string v;

    template <class T>
    Bytes& num(T x) {
        for (std::size_t i = 0; i < sizeof(T); ++i) v.push_back(char(std::uint8_t(std::uint64_t(x) >> (8 * i))));
        return *this;
    }
    Bytes& raw(std::string_view b) {
        v.append(b);
        return *this;
    }
    Bytes& raw(std::span<const std::uint8_t> b) {
        return raw(std::string_view(reinterpret_cast<const char*>(b.data()), b.size()));
    }
    Bytes& str(std::string_view s) { return num(std::uint32_t(s.size())).raw(s); }
    Bytes& u32_prefixed(const Bytes& inner) { return num(std::uint32_t(inner.v.size())).raw(std::string_view(inner.v)); }
};

inline std::string record(Op op, const Bytes& content) {
    Bytes r;
    r.num(std::uint8_t(op)).num(std::uint64_t(content.v.size())).raw(std::string_view(content.v));
    return r.v;
}

inline std::span<const std::uint8_t> bytes_of(std::string_view s) {
    return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Reads fields from a record's content, never past its end: a field that
// does not fit sets failed() (and reads as zero or empty), so a hostile
// length never reaches memory outside the content.
class Fields {
public:
    explicit Fields(std::string_view content) : rest_(content) {}

    template <class T>
    T num() {
        if (rest_.size() < sizeof(T)) return fail<T>();
        std::uint64_t x = 0;
        for (std::size_t i = 0; i < sizeof(T); ++i) x |= std::uint64_t(std::uint8_t(rest_[i])) << (8 * i);
        rest_.remove_prefix(sizeof(T));
        return T(x);
    }
    std::string_view bytes(std::uint64_t n) {
        if (rest_.size() < n) return fail<std::string_view>();
        const std::string_view b = rest_.substr(0, std::size_t(n));
        rest_.remove_prefix(std::size_t(n));
        return b;
    }
    std::string_view str() { return bytes(num<std::uint32_t>()); }
    std::string_view rest() {
        const std::string_view b = rest_;
        rest_ = {};
        return b;
    }
    bool failed() const { return failed_; }
    bool empty() const { return rest_.empty(); }
    // What a field inside this one found: the record does not hold together.
    void invalidate() { fail<int>(); }

private:
    template <class T>
    T fail() {
        failed_ = true;
        rest_ = {};
        return T{};
    }
    std::string_view rest_;
    bool failed_ = false;
};

}  // namespace vkfuse::io::mcap

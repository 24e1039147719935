// io/mcap_reader.hpp - reading MCAP files (mcap.dev/spec) that may be
// truncated, corrupt or hostile: the data section walked record by record in
// file order, every length checked against what is left of the file (and of
// its record) before anything is allocated, chunks decompressed only up to a
// bound, CRCs checked where the writer computed them. A file cut short, or
// corrupt from some record on, still gives every message before that record,
// and says where it stopped.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

namespace vkfuse::io::mcap {

// Where a message lies, to read it again later: the file offset of its
// Chunk record and the offset of its Message record in the chunk's
// (uncompressed) records; chunk 0: a record outside chunks, at file offset record.
struct MessageLocation {
    std::uint64_t chunk = 0;
    std::uint64_t record = 0;
};

struct SchemaInfo {
    std::uint16_t id = 0;
    std::string name, encoding, data;
};

struct ChannelInfo {
    std::uint16_t id = 0;
    std::uint16_t schema = 0;  // 0: none
    std::string topic, encoding;
    std::map<std::string, std::string> metadata;
};

struct Message {
    std::uint16_t channel = 0;
    std::uint32_t sequence = 0;
    std::uint64_t log_time = 0, publish_time = 0;
    std::string_view data;  // valid during the callback (or until the next read)
    MessageLocation at;
};

struct ReaderLimits {
    // The largest record or uncompressed chunk held in memory at once.
    std::uint64_t max_record_bytes = std::uint64_t(1) << 30;
};

class Reader {
public:
    // Opens path and checks the leading magic and Header record. Throws
    // Error(Io) when it cannot be opened, Error(Format) "path: ..." when it
    // is not an MCAP file.
    explicit Reader(const std::string& path, ReaderLimits limits = {});
    ~Reader();
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;

    const std::string& path() const { return path_; }
    const std::string& profile() const { return profile_; }

    struct Visitor {
        std::function<void(const Message&)> message;
        std::function<void(const std::string& name, const std::map<std::string, std::string>&)> metadata;
    };
    // Walks the data section in file order; schemas and channels are known
    // (schema(), channel()) by the time a message that uses them comes.
    // Returns "" when it reached Data End with the data section's CRC
    // intact, else one line saying where it stopped and why ("byte 1234:
    // Chunk: truncated (...)"): every record before that one was visited.
    // The visitor's own exceptions pass through.
    std::string scan(const Visitor& visitor);

    // Known once scan() met them; nullptr otherwise.
    const ChannelInfo* channel(std::uint16_t id) const;
    const SchemaInfo* schema(std::uint16_t id) const;

    // The message scan() reported at `at`, read again (its data valid until
    // the next read). Thread-safe. Throws Error(Format) naming the file and
    // byte when it is no longer there or no longer intact.
    Message read(const MessageLocation& at);

    struct File;

private:
    std::string path_;
    ReaderLimits limits_;
    std::unique_ptr<File> file_;
    std::string profile_;
    std::map<std::uint16_t, SchemaInfo> schemas_;
    std::map<std::uint16_t, ChannelInfo> channels_;
    std::mutex read_mutex_;
    // The last chunk read() decompressed: messages are read in file order.
    std::uint64_t cached_chunk_ = 0;
    std::string cached_records_;
    std::string unchunked_;  // read()'s last unchunked record
};

}  // namespace vkfuse::io::mcap

// mcap_writer.hpp - MCAP files (the robotics log format ROS 2's rosbag2,
// Foxglove and the MCAP tools read; the public specification at
// mcap.dev/spec), written as a stream: chunked, with message indexes, a
// summary (schemas, channels, statistics, chunk indexes), summary offsets and
// CRC-32s, so that readers seek in them and check them.
//
//   magic | Header | [Schema | Channel]* chunks, each followed by its
//   Message Index records | Data End | summary: Schema*, Channel*,
//   Statistics, Chunk Index* | Summary Offset* | Footer | magic
//
// Schemas and channels are written into the chunk in which they are first
// used (a reader streaming the file meets them before their messages) and
// again in the summary. Chunks are compressed as options say (zstd, lz4 or
// none); Metadata records go straight to the data section, indexed in the
// summary.
// What the records mean for a rig (topics, ROS 2 encodings) is the caller's.
#pragma once
#include <cstdint>
#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "io/mcap_compression.hpp"

namespace vkfuse::io::mcap {

// CRC-32 (ISO-HDLC, zlib's) of data, continuing from crc (0 to start).
std::uint32_t crc32(std::span<const std::uint8_t> data, std::uint32_t crc = 0);

struct WriterOptions {
    std::string profile;                    // e.g. "ros2"
    std::string library = "vkfuse";
    std::size_t chunk_bytes = 4u << 20;     // a chunk is closed once its records reach this size
    Compression compression = Compression::Zstd;
};

class Writer {
public:
    // Writes to `file` (opened for writing by the caller, who closes it
    // after finish()); `name` names it in errors. Throws Error(Io) for a
    // failed write.
    Writer(std::FILE* file, std::string name, WriterOptions options = {});

    // Ids from 1, in the order added.
    std::uint16_t add_schema(const std::string& name, const std::string& encoding, std::span<const std::uint8_t> data);
    std::uint16_t add_channel(std::uint16_t schema, const std::string& topic, const std::string& message_encoding,
                              const std::map<std::string, std::string>& metadata = {});
    // A Metadata record (name and string pairs), written at once.
    void add_metadata(const std::string& name, const std::map<std::string, std::string>& entries);
    // A message on channel (log and publish times in nanoseconds).
    void write(std::uint16_t channel, std::uint32_t sequence, std::uint64_t log_time, std::uint64_t publish_time,
               std::span<const std::uint8_t> data);
    // The last chunk, the summary and the footer. Nothing may be written after.
    void finish();

    std::uint64_t messages() const { return message_count_; }

private:
    struct Schema {
        std::string name, encoding;
        std::string data;       // bytes
        bool in_chunk = false;  // written into the current chunk already
    };
    struct Channel {
        std::uint16_t schema;
        std::string topic, encoding;
        std::map<std::string, std::string> metadata;
        bool in_chunk = false;
        std::uint64_t messages = 0;
    };
    struct ChunkIndex {
        std::uint64_t start_time, end_time, offset, length;
        std::map<std::uint16_t, std::uint64_t> index_offsets;
        std::uint64_t index_length, size, stored_size;  // size: uncompressed
    };
    struct MetadataIndex {
        std::uint64_t offset, length;
        std::string name;
    };

    void put(const std::string& bytes);  // to the file, counted and CRC'd
    void close_chunk();
    std::string schema_record(std::uint16_t id) const;
    std::string channel_record(std::uint16_t id) const;

    std::FILE* file_;
    std::string name_;
    WriterOptions options_;
    std::uint64_t offset_ = 0;     // bytes written
    std::uint32_t data_crc_ = 0;   // of every byte written, until Data End
    std::vector<Schema> schemas_;
    std::vector<Channel> channels_;
    std::vector<ChunkIndex> chunk_indexes_;
    std::vector<MetadataIndex> metadata_indexes_;
    // The open chunk: its records (bytes), each channel's (log time, offset in the records).
    std::string chunk_;
    std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_messages_;
    std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
    std::uint64_t message_count_ = 0, first_time_ = 0, last_time_ = 0;
    bool finished_ = false;
};

}  // namespace vkfuse::io::mcap

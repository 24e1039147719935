// MCAP files written as a stream (mcap_writer.hpp), in the record layer of
// mcap_records.hpp.
#include "io/mcap_writer.hpp"

#include "io/mcap_records.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

#include "vkfuse/core/error.hpp"

namespace vkfuse::io::mcap {
namespace {

const std::array<std::uint32_t, 256>& crc_table() {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    return table;
}

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> data, std::uint32_t crc) {
    const auto& t = crc_table();
    crc = ~crc;
    for (std::uint8_t b : data) crc = t[(crc ^ b) & 0xFF] ^ (crc >> 8);
    return ~crc;
}

Writer::Writer(std::FILE* file, std::string name, WriterOptions options)
    : file_(file), name_(std::move(name)), options_(std::move(options)) {
    put(std::string(std::begin(kMagic), std::end(kMagic)));
    Bytes header;
    header.str(options_.profile).str(options_.library);
    put(record(kHeader, header));
}

void Writer::put(const std::string& bytes) {
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
        throw Error(ErrorKind::Io, name_ + ": write failed (" + std::strerror(errno) + ")");
    if (!finished_) data_crc_ = crc32(bytes_of(bytes), data_crc_);
    offset_ += bytes.size();
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding,
                                 std::span<const std::uint8_t> data) {
    if (schemas_.size() >= 0xFFFF) throw Error(ErrorKind::InvalidArgument, name_ + ": more than 65535 schemas");
    schemas_.push_back({name, encoding, std::string(reinterpret_cast<const char*>(data.data()), data.size()), false});
    return std::uint16_t(schemas_.size());
}

std::uint16_t Writer::add_channel(std::uint16_t schema, const std::string& topic, const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
    if (schema < 1 || schema > schemas_.size())
        throw Error(ErrorKind::InvalidArgument, name_ + ": channel " + topic + " names schema " +
                                                    std::to_string(schema) + ", which was not added");
    if (channels_.size() >= 0xFFFF) throw Error(ErrorKind::InvalidArgument, name_ + ": more than 65535 channels");
    channels_.push_back({schema, topic, message_encoding, metadata, false, 0});
    return std::uint16_t(channels_.size());
}

std::string Writer::schema_record(std::uint16_t id) const {
    const Schema& s = schemas_[id - 1u];
    Bytes b;
    b.num(id).str(s.name).str(s.encoding).str(s.data);
    return record(kSchema, b);
}

std::string Writer::channel_record(std::uint16_t id) const {
    const Channel& c = channels_[id - 1u];
    Bytes meta;
    for (const auto& [k, v] : c.metadata) meta.str(k).str(v);
    Bytes b;
    b.num(id).num(c.schema).str(c.topic).str(c.encoding).u32_prefixed(meta);
    return record(kChannel, b);
}

void Writer::write(std::uint16_t channel, std::uint32_t sequence, std::uint64_t log_time, std::uint64_t publish_time,
                   std::span<const std::uint8_t> data) {
    if (finished_) throw Error(ErrorKind::InvalidArgument, name_ + ": a message after finish()");
    if (channel < 1 || channel > channels_.size())
        throw Error(ErrorKind::InvalidArgument, name_ + ": channel " + std::to_string(channel) + " was not added");
    Channel& c = channels_[channel - 1u];
    auto append = [this](const std::string& r) { chunk_ += r; };
    if (!schemas_[c.schema - 1u].in_chunk) {
        append(schema_record(c.schema));
        schemas_[c.schema - 1u].in_chunk = true;
    }
    if (!c.in_chunk) {
        append(channel_record(channel));
        c.in_chunk = true;
    }
    const bool first = chunk_messages_.empty();
    chunk_messages_[channel].emplace_back(log_time, chunk_.size());
    Bytes m;
    m.num(channel).num(sequence).num(log_time).num(publish_time).raw(data);
    append(record(kMessage, m));
    chunk_start_ = first ? log_time : std::min(chunk_start_, log_time);
    chunk_end_ = first ? log_time : std::max(chunk_end_, log_time);
    first_time_ = message_count_ == 0 ? log_time : std::min(first_time_, log_time);
    last_time_ = message_count_ == 0 ? log_time : std::max(last_time_, log_time);
    ++message_count_;
    ++c.messages;
    if (chunk_.size() >= options_.chunk_bytes) close_chunk();
}

void Writer::add_metadata(const std::string& name, const std::map<std::string, std::string>& entries) {
    if (finished_) throw Error(ErrorKind::InvalidArgument, name_ + ": metadata after finish()");
    Bytes map;
    for (const auto& [k, v] : entries) map.str(k).str(v);
    Bytes b;
    b.str(name).u32_prefixed(map);
    const std::string r = record(kMetadata, b);
    metadata_indexes_.push_back({offset_, r.size(), name});
    put(r);
}

void Writer::close_chunk() {
    if (chunk_messages_.empty()) return;
    const std::string stored = compress(options_.compression, chunk_);
    ChunkIndex index{chunk_start_, chunk_end_, offset_, 0, {}, 0, chunk_.size(), stored.size()};
    Bytes chunk;
    chunk.num(chunk_start_).num(chunk_end_).num(std::uint64_t(chunk_.size())).num(crc32(bytes_of(chunk_)));
    chunk.str(to_string(options_.compression)).num(std::uint64_t(stored.size())).raw(std::string_view(stored));
    const std::string chunk_record = record(kChunk, chunk);
    index.length = chunk_record.size();
    put(chunk_record);
    const std::uint64_t indexes_start = offset_;
    for (const auto& [channel, entries] : chunk_messages_) {
        Bytes list;
        for (const auto& [time, at] : entries) list.num(time).num(at);
        Bytes b;
        b.num(channel).u32_prefixed(list);
        index.index_offsets[channel] = offset_;
        put(record(kMessageIndex, b));
    }
    index.index_length = offset_ - indexes_start;
    chunk_indexes_.push_back(index);
    chunk_.clear();
    chunk_messages_.clear();
    for (Schema& s : schemas_) s.in_chunk = false;
    for (Channel& c : channels_) c.in_chunk = false;
}

void Writer::finish() {
    if (finished_) return;
    close_chunk();
    Bytes end;
    end.num(data_crc_);
    put(record(kDataEnd, end));
    finished_ = true;  // the data section's CRC is complete; the summary's is its own
    const std::uint64_t summary_start = offset_;
    std::uint32_t summary_crc = 0;
    auto summary = [&](const std::string& r) {
        summary_crc = crc32(bytes_of(r), summary_crc);
        put(r);
    };
    struct Group {
        Op op;
        std::uint64_t start, length;
    };
    std::vector<Group> groups;
    auto group = [&](Op op, auto&& write_records) {
        const std::uint64_t start = offset_;
        write_records();
        if (offset_ > start) groups.push_back({op, start, offset_ - start});
    };
    group(kSchema, [&] {
        for (std::size_t i = 0; i < schemas_.size(); ++i) summary(schema_record(std::uint16_t(i + 1)));
    });
    group(kChannel, [&] {
        for (std::size_t i = 0; i < channels_.size(); ++i) summary(channel_record(std::uint16_t(i + 1)));
    });
    group(kStatistics, [&] {
        Bytes counts;
        for (std::size_t i = 0; i < channels_.size(); ++i) counts.num(std::uint16_t(i + 1)).num(channels_[i].messages);
        Bytes s;
        s.num(message_count_).num(std::uint16_t(schemas_.size())).num(std::uint32_t(channels_.size()));
        s.num(std::uint32_t(0)).num(std::uint32_t(metadata_indexes_.size())).num(std::uint32_t(chunk_indexes_.size()));
        s.num(first_time_).num(last_time_).u32_prefixed(counts);
        summary(record(kStatistics, s));
    });
    group(kMetadataIndex, [&] {
        for (const MetadataIndex& m : metadata_indexes_) {
            Bytes b;
            b.num(m.offset).num(m.length).str(m.name);
            summary(record(kMetadataIndex, b));
        }
    });
    group(kChunkIndex, [&] {
        for (const ChunkIndex& c : chunk_indexes_) {
            Bytes offsets;
            for (const auto& [channel, at] : c.index_offsets) offsets.num(channel).num(at);
            Bytes b;
            b.num(c.start_time).num(c.end_time).num(c.offset).num(c.length).u32_prefixed(offsets);
            b.num(c.index_length).str(to_string(options_.compression)).num(c.stored_size).num(c.size);
            summary(record(kChunkIndex, b));
        }
    });
    const std::uint64_t offsets_start = offset_;
    for (const Group& g : groups) {
        Bytes b;
        b.num(std::uint8_t(g.op)).num(g.start).num(g.length);
        summary(record(kSummaryOffset, b));
    }
    // The footer's CRC covers the summary and the footer up to the CRC itself.
    Bytes footer_head;
    footer_head.num(std::uint8_t(kFooter)).num(std::uint64_t(8 + 8 + 4)).num(summary_start).num(offsets_start);
    summary_crc = crc32(bytes_of(footer_head.v), summary_crc);
    Bytes footer = footer_head;
    footer.num(summary_crc);
    put(footer.v);
    put(std::string(std::begin(kMagic), std::end(kMagic)));
}

}  // namespace vkfuse::io::mcap

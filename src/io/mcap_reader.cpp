// MCAP files read defensively (mcap_reader.hpp): each record's length is
// checked against the bytes left before it is read, each field against its
// record (Fields), each chunk's claimed size against the limit before it is
// decompressed.
#include "io/mcap_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "io/mcap_compression.hpp"
#include "io/mcap_records.hpp"
#include "io/mcap_writer.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::io::mcap {

struct Reader::File {
    int fd = -1;
    std::uint64_t size = 0;
    ~File() {
        if (fd >= 0) ::close(fd);
    }
    // n bytes at offset (the caller checked they lie within size).
    std::string read(std::uint64_t offset, std::uint64_t n, const std::string& path) const {
        std::string out(std::size_t(n), '\0');
        std::size_t done = 0;
        while (done < out.size()) {
            const ssize_t r = ::pread(fd, out.data() + done, out.size() - done, off_t(offset + done));
            if (r < 0 && errno == EINTR) continue;
            if (r < 0) throw Error(ErrorKind::Io, path + ": cannot read: " + std::strerror(errno));
            if (r == 0) throw Error(ErrorKind::Format, path + ": truncated at byte " + std::to_string(offset + done) +
                                                           " (the file shrank while it was read)");
            done += std::size_t(r);
        }
        return out;
    }
};

namespace {

std::string op_name(std::uint8_t op) {
    static const char* const names[] = {"",        "Header",        "Footer",     "Schema",       "Channel",
                                        "Message", "Chunk",         "Message Index", "Chunk Index", "Attachment",
                                        "Attachment Index", "Statistics", "Metadata", "Metadata Index",
                                        "Summary Offset", "Data End"};
    if (op < std::size(names) && op > 0) return names[op];
    char text[16];
    std::snprintf(text, sizeof text, "opcode 0x%02x", op);
    return text;
}

// A problem with one record: where scan() stops.
struct Stop {
    std::string why;
};

std::map<std::string, std::string> string_map(Fields& f) {
    Fields entries(f.bytes(f.num<std::uint32_t>()));
    std::map<std::string, std::string> out;
    while (!entries.empty() && !entries.failed()) {
        const std::string_view k = entries.str();
        const std::string_view v = entries.str();
        out[std::string(k)] = std::string(v);
    }
    if (entries.failed()) f.invalidate();
    return out;
}

struct ChunkFields {
    std::uint64_t uncompressed_size = 0;
    std::uint32_t crc = 0;
    Compression compression = Compression::None;
    std::string_view stored;
};

ChunkFields chunk_fields(std::string_view content, std::uint64_t limit) {
    Fields f(content);
    f.num<std::uint64_t>();
    f.num<std::uint64_t>();
    ChunkFields c;
    c.uncompressed_size = f.num<std::uint64_t>();
    c.crc = f.num<std::uint32_t>();
    const std::string_view name = f.str();
    const std::uint64_t stored = f.num<std::uint64_t>();
    if (f.failed()) throw Stop{"its fields run past the record"};
    const auto compression = parse_compression(name);
    if (!compression) throw Stop{"compression \"" + std::string(name.substr(0, 32)) + "\", which this reader does not know"};
    c.compression = *compression;
    c.stored = f.bytes(stored);
    if (f.failed()) throw Stop{"its records claim " + std::to_string(stored) + " bytes, more than the record holds"};
    if (c.uncompressed_size > limit)
        throw Stop{"it claims " + std::to_string(c.uncompressed_size) + " bytes uncompressed, more than the " +
                   std::to_string(limit) + " this reader takes"};
    return c;
}

std::string chunk_records(const ChunkFields& c, const std::string& what) {
    std::string records;
    try {
        records = decompress(c.compression, c.stored, std::size_t(c.uncompressed_size), what);
    } catch (const Error& e) {
        throw Stop{e.what()};
    }
    if (c.crc != 0 && crc32(bytes_of(records)) != c.crc) throw Stop{"its records' CRC-32 differs from the one it carries"};
    return records;
}

Message message_fields(std::string_view content) {
    Fields f(content);
    Message m;
    m.channel = f.num<std::uint16_t>();
    m.sequence = f.num<std::uint32_t>();
    m.log_time = f.num<std::uint64_t>();
    m.publish_time = f.num<std::uint64_t>();
    if (f.failed()) throw Stop{"its fields run past the record"};
    m.data = f.rest();
    return m;
}

}  // namespace

Reader::Reader(const std::string& path, ReaderLimits limits) : path_(path), limits_(limits), file_(std::make_unique<File>()) {
    file_->fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (file_->fd < 0) throw Error(ErrorKind::Io, path + ": cannot open: " + std::strerror(errno));
    struct stat st {};
    if (::fstat(file_->fd, &st) != 0 || !S_ISREG(st.st_mode)) throw Error(ErrorKind::Io, path + ": not a regular file");
    file_->size = std::uint64_t(st.st_size);
    const auto not_mcap = [&](const std::string& why) { throw Error(ErrorKind::Format, path + ": not an MCAP file (" + why + ")"); };
    if (file_->size < kMagicSize + kRecordHead) not_mcap("too short");
    const std::string head = file_->read(0, kMagicSize + kRecordHead, path);
    if (std::memcmp(head.data(), kMagic, kMagicSize) != 0) not_mcap("no MCAP magic at its start");
    Fields h(std::string_view(head).substr(kMagicSize));
    if (h.num<std::uint8_t>() != kHeader) not_mcap("no Header record after the magic");
    const std::uint64_t length = h.num<std::uint64_t>();
    if (length > file_->size - kMagicSize - kRecordHead || length > (1u << 20)) not_mcap("its Header record is truncated");
    const std::string content = file_->read(kMagicSize + kRecordHead, length, path);
    Fields header(content);
    profile_ = std::string(header.str());
    if (header.failed()) not_mcap("its Header record's fields run past it");
}

Reader::~Reader() = default;

const ChannelInfo* Reader::channel(std::uint16_t id) const {
    const auto it = channels_.find(id);
    return it == channels_.end() ? nullptr : &it->second;
}

const SchemaInfo* Reader::schema(std::uint16_t id) const {
    const auto it = schemas_.find(id);
    return it == schemas_.end() ? nullptr : &it->second;
}

std::string Reader::scan(const Visitor& visitor) {
    // Schema, Channel and Message records, in or out of chunks.
    auto take = [&](std::uint8_t op, std::string_view content, MessageLocation at) {
        Fields f(content);
        if (op == kSchema) {
            SchemaInfo s;
            s.id = f.num<std::uint16_t>();
            s.name = f.str();
            s.encoding = f.str();
            s.data = f.bytes(f.num<std::uint32_t>());
            if (f.failed()) throw Stop{"its fields run past the record"};
            if (s.id == 0) throw Stop{"schema id 0"};
            const SchemaInfo* had = schema(s.id);
            if (had && (had->name != s.name || had->encoding != s.encoding || had->data != s.data))
                throw Stop{"schema " + std::to_string(s.id) + " redefined differently"};
            schemas_[s.id] = std::move(s);
        } else if (op == kChannel) {
            ChannelInfo c;
            c.id = f.num<std::uint16_t>();
            c.schema = f.num<std::uint16_t>();
            c.topic = f.str();
            c.encoding = f.str();
            c.metadata = string_map(f);
            if (f.failed()) throw Stop{"its fields run past the record"};
            if (c.schema != 0 && !schema(c.schema))
                throw Stop{"channel " + c.topic.substr(0, 200) + " names schema " + std::to_string(c.schema) +
                           ", which no Schema record before it declared"};
            const ChannelInfo* had = channel(c.id);
            if (had && (had->schema != c.schema || had->topic != c.topic || had->encoding != c.encoding))
                throw Stop{"channel " + std::to_string(c.id) + " redefined differently"};
            channels_[c.id] = std::move(c);
        } else if (op == kMessage) {
            Message m = message_fields(content);
            if (!channel(m.channel))
                throw Stop{"a message on channel " + std::to_string(m.channel) + ", which no Channel record before it declared"};
            m.at = at;
            if (visitor.message) visitor.message(m);
        }
    };

    std::uint32_t crc = 0;
    std::uint64_t offset = kMagicSize;
    crc = crc32(bytes_of(std::string_view(reinterpret_cast<const char*>(kMagic), kMagicSize)), crc);
    const std::uint64_t size = file_->size;
    std::uint8_t op = 0;
    try {
        for (bool first = true;; first = false) {
            if (offset == size) throw Stop{"the file ends without a Data End record (truncated)"};
            if (size - offset < kRecordHead) throw Stop{"truncated: a record's head cut short"};
            const std::string head = file_->read(offset, kRecordHead, path_);
            Fields h(head);
            op = h.num<std::uint8_t>();
            const std::uint64_t length = h.num<std::uint64_t>();
            if (length > size - offset - kRecordHead)
                throw Stop{"truncated: it claims " + std::to_string(length) + " bytes, " +
                           std::to_string(size - offset - kRecordHead) + " remain in the file"};
            if (first && op != kHeader) throw Stop{"expected the Header record"};
            const bool needed = op == kHeader || op == kSchema || op == kChannel || op == kMessage || op == kChunk ||
                                op == kMetadata || op == kDataEnd;
            if (needed && length > limits_.max_record_bytes)
                throw Stop{std::to_string(length) + " bytes, more than the " + std::to_string(limits_.max_record_bytes) +
                           " this reader takes"};
            if (op == kDataEnd) {
                const std::string content = file_->read(offset + kRecordHead, std::min<std::uint64_t>(length, 4), path_);
                Fields f(content);
                const std::uint32_t stored = f.num<std::uint32_t>();
                if (f.failed()) throw Stop{"its CRC runs past the record"};
                if (stored != 0 && stored != crc) throw Stop{"the data section's CRC-32 differs from the one it carries"};
                return "";
            }
            crc = crc32(bytes_of(head), crc);
            if (!needed) {  // skipped, but counted in the data section's CRC
                for (std::uint64_t done = 0; done < length;) {
                    const std::uint64_t n = std::min<std::uint64_t>(length - done, 1u << 20);
                    crc = crc32(bytes_of(file_->read(offset + kRecordHead + done, n, path_)), crc);
                    done += n;
                }
            } else {
                const std::string content = file_->read(offset + kRecordHead, length, path_);
                crc = crc32(bytes_of(content), crc);
                if (op == kChunk) {
                    const std::string records =
                        chunk_records(chunk_fields(content, limits_.max_record_bytes), "its records");
                    for (std::uint64_t at = 0; at < records.size();) {
                        Fields r(std::string_view(records).substr(std::size_t(at)));
                        const std::uint8_t inner = r.num<std::uint8_t>();
                        const std::uint64_t n = r.num<std::uint64_t>();
                        if (r.failed() || n > records.size() - at - kRecordHead)
                            throw Stop{"the record at byte " + std::to_string(at) + " of its records runs past them"};
                        take(inner, std::string_view(records).substr(std::size_t(at + kRecordHead), std::size_t(n)),
                             {offset, at});
                        at += kRecordHead + n;
                    }
                } else if (op == kMetadata) {
                    Fields f(content);
                    const std::string name(f.str());
                    const auto entries = string_map(f);
                    if (f.failed()) throw Stop{"its fields run past the record"};
                    if (visitor.metadata) visitor.metadata(name, entries);
                } else if (op != kHeader) {
                    take(op, content, {0, offset});
                }
            }
            offset += kRecordHead + length;
        }
    } catch (const Stop& stop) {
        return "byte " + std::to_string(offset) + (op ? ": " + op_name(op) : std::string()) + ": " + stop.why;
    }
}

Message Reader::read(const MessageLocation& at) {
    std::lock_guard lock(read_mutex_);
    const std::string where = path_ + ": byte " + std::to_string(at.chunk ? at.chunk : at.record);
    try {
        auto record_at = [&](std::uint64_t offset, std::uint8_t want) {
            if (offset > file_->size || file_->size - offset < kRecordHead) throw Stop{"no record there"};
            const std::string head = file_->read(offset, kRecordHead, path_);
            Fields h(head);
            const std::uint8_t op = h.num<std::uint8_t>();
            const std::uint64_t length = h.num<std::uint64_t>();
            if (op != want) throw Stop{"a " + op_name(op) + " record where a " + op_name(want) + " was"};
            if (length > file_->size - offset - kRecordHead || length > limits_.max_record_bytes)
                throw Stop{"the record runs past the file"};
            return file_->read(offset + kRecordHead, length, path_);
        };
        if (at.chunk == 0) {
            unchunked_ = record_at(at.record, kMessage);
            return message_fields(unchunked_);
        }
        if (cached_chunk_ != at.chunk || cached_records_.empty()) {
            cached_records_.clear();
            cached_records_ = chunk_records(chunk_fields(record_at(at.chunk, kChunk), limits_.max_record_bytes), where);
            cached_chunk_ = at.chunk;
        }
        Fields r(std::string_view(cached_records_).substr(std::min<std::size_t>(at.record, cached_records_.size())));
        const std::uint8_t op = r.num<std::uint8_t>();
        const std::uint64_t n = r.num<std::uint64_t>();
        if (r.failed() || op != kMessage || n > cached_records_.size() - at.record - kRecordHead)
            throw Stop{"no Message record at byte " + std::to_string(at.record) + " of the chunk's records"};
        Message m = message_fields(std::string_view(cached_records_).substr(std::size_t(at.record + kRecordHead), std::size_t(n)));
        m.at = at;
        return m;
    } catch (const Stop& stop) {
        throw Error(ErrorKind::Format, where + ": " + stop.why);
    }
}

}  // namespace vkfuse::io::mcap

// io/mcap_compression.hpp - the chunk compressions MCAP names: "" (none),
// "zstd" (a zstd frame) and "lz4" (an LZ4 frame, lz4frame.h, not raw blocks).
#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace vkfuse::io::mcap {

enum class Compression { None, Zstd, Lz4 };

// The name a Chunk record carries ("", "zstd", "lz4"), and back (nullopt for
// a name this reader does not know).
std::string_view to_string(Compression c);
std::optional<Compression> parse_compression(std::string_view name);
// As options spell it: "none", "zstd", "lz4".
std::string_view option_name(Compression c);
std::optional<Compression> parse_compression_option(std::string_view name);

std::string compress(Compression c, std::string_view data);
// Exactly `size` bytes from data, or Error(Format) "<what>: ..." when data is
// not a valid frame of c or does not hold exactly size bytes. The caller
// bounds size before it is allocated.
std::string decompress(Compression c, std::string_view data, std::size_t size, const std::string& what);

}  // namespace vkfuse::io::mcap

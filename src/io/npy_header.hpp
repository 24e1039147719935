// io/npy_header.hpp - the NumPy .npy header: magic, version, dict literal.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vkfuse::io {

// The element types vkfuse reads (docs/spec.md, "Images").
enum class NpyKind { F4, F8, U1, U2 };

struct NpyHeader {
    NpyKind kind = NpyKind::F4;
    bool big_endian = false;
    bool fortran_order = false;
    std::vector<std::uint64_t> shape;
    std::size_t data_offset = 0;  // where the array data starts in the file
};

std::size_t item_size(NpyKind);
std::string_view type_name(NpyKind);  // "float32", "uint8", ...

// Parses the header of a .npy file (versions 1.0, 2.0, 3.0). Every length and
// field is checked against file; anything malformed or unsupported throws
// Error(Format) "path: <problem>". The shape is returned as written (any rank).
NpyHeader parse_npy_header(const std::vector<unsigned char>& file, const std::string& path);

// The longest header accepted: NumPy writes under 200 bytes for the dtypes
// read here; a length field claiming more is corrupt, not a reason to read.
inline constexpr std::size_t kMaxNpyHeaderBytes = std::size_t(1) << 20;

// From a file's first bytes (prefix_size of them, at least 12 when the file
// has that many): magic and version checked, the header's total length
// (magic to the end of the dict, i.e. where the data starts), checked against
// file_size and kMaxNpyHeaderBytes. Throws Error(Format) as parse_npy_header.
std::size_t npy_header_size(const unsigned char* prefix, std::size_t prefix_size, std::uint64_t file_size,
                            const std::string& path);

// parse_npy_header on the first size bytes of a file of file_size bytes
// (data holds at least the header, npy_header_size of them).
NpyHeader parse_npy_header(const unsigned char* data, std::size_t size, std::uint64_t file_size,
                           const std::string& path);

// The bytes of a version 1.0 header for a little-endian float32 array of
// shape, padded as NumPy pads it (total length a multiple of 64).
std::string format_npy_header(const std::vector<std::uint64_t>& shape);

}  // namespace vkfuse::io

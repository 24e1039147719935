// npy_bytes.hpp - hand-made .npy files, valid or broken on purpose, for the
// reader tests and the command-line bad-input tests. Header-only.
#pragma once
#include <cstddef>
#include <string>

namespace vkfuse::test {

// A .npy file exactly as NumPy lays it out, from its dict literal and data.
inline std::string npy_bytes(const std::string& dict, const std::string& data, int major = 1) {
    std::size_t length_bytes = major == 1 ? 2 : 4;
    std::string header = dict;
    std::size_t total = 8 + length_bytes + header.size() + 1;
    header.append((64 - total % 64) % 64, ' ');
    header += '\n';
    std::string out = "\x93NUMPY";
    out += char(major);
    out += char(0);
    for (std::size_t i = 0; i < length_bytes; ++i) out += char((header.size() >> (8 * i)) & 0xff);
    return out + header + data;
}

inline std::string dict_of(const std::string& descr, bool fortran, const std::string& shape) {
    return "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': " + shape +
           ", }";
}

}  // namespace vkfuse::test

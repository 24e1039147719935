// fuzz_image.hpp - what the PNG and NPY targets check about one decode.
#pragma once
#include <string>

#include "fuzz_targets.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::fuzz {

// decode() either returns an image whose size matches its shape (C in {1, 3},
// then checked for NaN/Inf as read_image does) or throws an Error of kind
// Format or Numeric whose single line starts with "<name>: ".
template <class Decode>
void decode_checked(const std::string& name, Decode decode) {
    try {
        const Image image = decode();
        if (image.height < 1 || image.width < 1 || (image.channels != 1 && image.channels != 3) ||
            image.data.size() != image.pixels() * std::size_t(image.channels))
            violated(name.c_str(), "decoded image is inconsistent with its shape");
        io::check_finite(image, name);
    } catch (const Error& e) {
        const std::string what = e.what();
        if (e.kind() != ErrorKind::Format && e.kind() != ErrorKind::Numeric) violated("error kind", what.c_str());
        if (what.rfind(name + ": ", 0) != 0 || what.find('\n') != std::string::npos)
            violated("error message", what.c_str());
    }
}

}  // namespace vkfuse::fuzz

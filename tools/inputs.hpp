// inputs.hpp - the images named on a command line, read and checked.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "io/image_header.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::cli {

struct Input {
    std::string path;
    Image image;
};

// An input whose header has been read and checked, its pixels not yet.
struct InputHeader {
    std::string path;
    io::ImageHeader header;
};

// Reads every path's header (io::read_image_header): a missing, corrupt or
// oversized input is reported before any pixel is decoded or memory planned.
std::vector<InputHeader> read_headers(const std::vector<std::string>& paths);

// Reads every path (io::read_image, which also rejects NaN/Inf) before any
// computation, so a bad input is reported before work or output starts.
std::vector<Input> read_inputs(const std::vector<std::string>& paths);

// "HxWxC", as shapes appear in messages.
std::string shape_text(const Image& image);

// Throws Error(Shape) "<input>: shape 64x32x3 differs from <role><reference>'s 64x64x3";
// role is e.g. "the background " or empty.
void require_same_shape(const Input& input, const Input& reference, std::string_view role = "");
void require_same_shape(const InputHeader& input, const InputHeader& reference, std::string_view role = "");

}  // namespace vkfuse::cli

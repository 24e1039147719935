#include "inputs.hpp"

#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::cli {
namespace {

std::string shape_text(int height, int width, int channels) {
    return std::to_string(height) + "x" + std::to_string(width) + "x" + std::to_string(channels);
}

[[noreturn]] void shape_mismatch(const std::string& input, const std::string& input_shape, const std::string& reference,
                    const std::string& reference_shape, std::string_view role) {
    throw Error(ErrorKind::Shape, input + ": shape " + input_shape + " differs from " + std::string(role) + reference +
                                      "'s " + reference_shape);
}

}  // namespace

std::vector<InputHeader> read_headers(const std::vector<std::string>& paths) {
    std::vector<InputHeader> headers;
    headers.reserve(paths.size());
    for (const std::string& path : paths) headers.push_back({path, io::read_image_header(path)});
    return headers;
}

std::vector<Input> read_inputs(const std::vector<std::string>& paths) {
    std::vector<Input> inputs;
    inputs.reserve(paths.size());
    for (const std::string& path : paths) inputs.push_back({path, io::read_image(path)});
    return inputs;
}

std::string shape_text(const Image& image) { return shape_text(image.height, image.width, image.channels); }

void require_same_shape(const Input& input, const Input& reference, std::string_view role) {
    if (input.image.same_shape(reference.image)) return;
    shape_mismatch(input.path, shape_text(input.image), reference.path, shape_text(reference.image), role);
}

void require_same_shape(const InputHeader& input, const InputHeader& reference, std::string_view role) {
    const io::ImageHeader &a = input.header, &b = reference.header;
    if (a.height == b.height && a.width == b.width && a.channels == b.channels) return;
    shape_mismatch(input.path, shape_text(a.height, a.width, a.channels), reference.path,
                   shape_text(b.height, b.width, b.channels), role);
}

}  // namespace vkfuse::cli

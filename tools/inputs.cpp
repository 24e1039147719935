#include "inputs.hpp"

#include "vkfuse/error.hpp"
#include "vkfuse/io.hpp"

namespace vkfuse::cli {

std::vector<Input> read_inputs(const std::vector<std::string>& paths) {
    std::vector<Input> inputs;
    inputs.reserve(paths.size());
    for (const std::string& path : paths) inputs.push_back({path, io::read_image(path)});
    return inputs;
}

std::string shape_text(const Image& image) {
    return std::to_string(image.height) + "x" + std::to_string(image.width) + "x" + std::to_string(image.channels);
}

void require_same_shape(const Input& input, const Input& reference, std::string_view role) {
    if (input.image.same_shape(reference.image)) return;
    throw Error(ErrorKind::Shape, input.path + ": shape " + shape_text(input.image) + " differs from " +
                                      std::string(role) + reference.path + "'s " + shape_text(reference.image));
}

}  // namespace vkfuse::cli

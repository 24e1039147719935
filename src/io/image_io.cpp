// read_image / write_image / check_finite: choose the format by extension and
// apply the checks every image crossing the file boundary must pass.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "io/atomic_write.hpp"
#include "io/file_bytes.hpp"
#include "io/image_header.hpp"
#include "io/io_error.hpp"
#include "io/npy.hpp"
#include "io/png.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::io {
namespace {

enum class Format { Png, Npy };

Format format_of(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".png") return Format::Png;
    if (ext == ".npy") return Format::Npy;
    fail(ErrorKind::InvalidArgument, path,
         "unknown image format " + (ext.empty() ? std::string("(no extension)") : "'" + ext + "'") +
             ": expected .png or .npy");
}

void check_writable(const std::string& path, const Image& image, Format format) {
    bool consistent = image.height > 0 && image.width > 0 && image.channels > 0 &&
                      image.data.size() == image.pixels() * std::size_t(image.channels);
    if (!consistent)
        fail(ErrorKind::InvalidArgument, path,
             "cannot write a " + std::to_string(image.height) + "x" + std::to_string(image.width) + "x" +
                 std::to_string(image.channels) + " image holding " + std::to_string(image.data.size()) + " values");
    if (format == Format::Png && image.channels != 1 && image.channels != 3)
        fail(ErrorKind::InvalidArgument, path,
             "a PNG holds 1 or 3 channels, not " + std::to_string(image.channels));
    // A PNG cannot represent NaN or Inf; a .npy stores whatever was computed.
    if (format == Format::Png) check_finite(image, path);
}

}  // namespace

Image read_image(const std::string& path) {
    Format format = format_of(path);
    InputFile file(path);
    Image image = format == Format::Png ? read_png(file) : read_npy(file);
    check_finite(image, path);
    return image;
}

ImageHeader read_image_header(const std::string& path) {
    Format format = format_of(path);
    InputFile file(path);
    return format == Format::Png ? read_png_header(file) : read_npy_header(file);
}

void write_image(const std::string& path, const Image& image) {
    Format format = format_of(path);
    check_writable(path, image, format);
    write_atomically(path, [&](std::FILE* out) {
        if (format == Format::Png) write_png(out, image, path);
        else write_npy(out, image, path);
    });
}

void check_image_extension(const std::string& path) { format_of(path); }

void check_finite(const Image& image, const std::string& what) {
    auto bad = std::find_if(image.data.begin(), image.data.end(), [](float v) { return !std::isfinite(v); });
    if (bad == image.data.end()) return;
    std::size_t i = std::size_t(bad - image.data.begin());
    std::size_t channels = std::size_t(std::max(image.channels, 1));
    std::size_t width = std::size_t(std::max(image.width, 1));
    std::size_t pixel = i / channels;
    std::string value = std::isnan(*bad) ? "NaN" : (*bad > 0 ? "Inf" : "-Inf");
    throw Error(ErrorKind::Numeric, what + ": " + value + " at row " + std::to_string(pixel / width) + ", column " +
                                        std::to_string(pixel % width) + ", channel " + std::to_string(i % channels));
}

}  // namespace vkfuse::io

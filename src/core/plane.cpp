// Moving single channels in and out of interleaved images.
#include "core/plane.hpp"

#include <stdexcept>

namespace vkfuse::core {

Plane extract_channel(const ImageD& image, int c) {
    Plane p(image.height, image.width);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) p.at(y, x) = image.at(y, x, c);
    return p;
}

void insert_channel(const Plane& plane, ImageD& image, int c) {
    if (plane.height != image.height || plane.width != image.width)
        throw std::logic_error("insert_channel: plane and image sizes differ");
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) image.at(y, x, c) = plane.at(y, x);
}

Plane crop(const Plane& p, int height, int width) {
    if (height > p.height || width > p.width) throw std::logic_error("crop: larger than the plane");
    Plane out(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) out.at(y, x) = p.at(y, x);
    return out;
}

}  // namespace vkfuse::core

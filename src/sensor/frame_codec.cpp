// YUYV and Motion-JPEG to RGB and back (frame_codec.hpp).
#include "frame_codec.hpp"

#include <algorithm>
#include <csetjmp>
#include <cstdlib>
#include <cstdio>

#include <jpeglib.h>

namespace vkfuse {
namespace {

std::uint8_t clamp8(int v) { return std::uint8_t(std::clamp(v, 0, 255)); }

// libjpeg reports errors through error_exit, which must not return: it jumps
// back to the decoder's frame. No C++ object with a destructor lives between
// the setjmp and the libjpeg calls.
struct JpegErrors {
    jpeg_error_mgr mgr{};
    std::jmp_buf back{};
    char message[JMSG_LENGTH_MAX]{};
};

void on_error(j_common_ptr info) {
    auto* e = reinterpret_cast<JpegErrors*>(info->err);
    info->err->format_message(info, e->message);
    std::longjmp(e->back, 1);
}

void on_message(j_common_ptr info, int level) {
    // Warnings (level -1) mark corrupt data; keep the first as the reason.
    if (level < 0) {
        auto* e = reinterpret_cast<JpegErrors*>(info->err);
        if (info->err->num_warnings++ == 0) info->err->format_message(info, e->message);
    }
}

// Decodes into rgb (sized by the caller); returns 0, or 1 with errors->message set.
int decode(const std::uint8_t* data, unsigned long size, int width, int height, std::uint8_t* rgb,
           JpegErrors* errors) {
    jpeg_decompress_struct info{};
    info.err = jpeg_std_error(&errors->mgr);
    errors->mgr.error_exit = on_error;
    errors->mgr.emit_message = on_message;
    if (setjmp(errors->back)) {
        jpeg_destroy_decompress(&info);
        return 1;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, data, size);
    jpeg_read_header(&info, TRUE);
    info.out_color_space = JCS_RGB;
    jpeg_start_decompress(&info);
    if (int(info.output_width) != width || int(info.output_height) != height || info.output_components != 3) {
        std::snprintf(errors->message, sizeof errors->message, "a %ux%u frame where %dx%d was negotiated",
                      info.output_width, info.output_height, width, height);
        jpeg_destroy_decompress(&info);
        return 1;
    }
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = rgb + std::size_t(info.output_scanline) * std::size_t(width) * 3;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    const bool warned = errors->mgr.num_warnings > 0;
    jpeg_destroy_decompress(&info);
    return warned ? 1 : 0;
}

}  // namespace

bool yuyv_to_rgb(std::span<const std::uint8_t> yuyv, int width, int height, std::vector<std::uint8_t>& rgb) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (width % 2 != 0 || yuyv.size() < pixels * 2) return false;
    rgb.resize(pixels * 3);
    std::uint8_t* out = rgb.data();
    for (std::size_t p = 0; p < pixels; p += 2) {
        const std::uint8_t* q = yuyv.data() + p * 2;
        const int d = q[1] - 128, e = q[3] - 128;
        const int red = 409 * e + 128, green = -100 * d - 208 * e + 128, blue = 516 * d + 128;
        for (int k = 0; k < 2; ++k) {
            const int c = 298 * (q[2 * k] - 16);
            *out++ = clamp8((c + red) >> 8);
            *out++ = clamp8((c + green) >> 8);
            *out++ = clamp8((c + blue) >> 8);
        }
    }
    return true;
}

std::vector<std::uint8_t> rgb_to_yuyv(std::span<const std::uint8_t> rgb, int width, int height) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    std::vector<std::uint8_t> out(pixels * 2);
    const auto luma = [](const std::uint8_t* c) { return clamp8(((66 * c[0] + 129 * c[1] + 25 * c[2] + 128) >> 8) + 16); };
    for (std::size_t p = 0; p < pixels; p += 2) {
        const std::uint8_t* a = rgb.data() + p * 3;
        const std::uint8_t* b = a + 3;
        const int r = (a[0] + b[0] + 1) / 2, g = (a[1] + b[1] + 1) / 2, bl = (a[2] + b[2] + 1) / 2;
        out[p * 2] = luma(a);
        out[p * 2 + 1] = clamp8(((-38 * r - 74 * g + 112 * bl + 128) >> 8) + 128);
        out[p * 2 + 2] = luma(b);
        out[p * 2 + 3] = clamp8(((112 * r - 94 * g - 18 * bl + 128) >> 8) + 128);
    }
    return out;
}

std::vector<std::uint8_t> rgb_to_jpeg(std::span<const std::uint8_t> rgb, int width, int height, int quality) {
    jpeg_compress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);  // encoding memory we own fails only on a bug: libjpeg's exit() stands
    jpeg_create_compress(&info);
    unsigned char* out = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&info, &out, &size);
    info.image_width = JDIMENSION(width);
    info.image_height = JDIMENSION(height);
    info.input_components = 3;
    info.in_color_space = JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, quality, TRUE);
    info.comp_info[0].h_samp_factor = 2;  // 4:2:2
    info.comp_info[0].v_samp_factor = 1;
    jpeg_start_compress(&info, TRUE);
    while (info.next_scanline < info.image_height) {
        JSAMPROW row = const_cast<std::uint8_t*>(rgb.data()) + std::size_t(info.next_scanline) * std::size_t(width) * 3;
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    std::vector<std::uint8_t> jpeg(out, out + size);
    jpeg_destroy_compress(&info);
    std::free(out);
    return jpeg;
}

bool mjpeg_to_rgb(std::span<const std::uint8_t> jpeg, int width, int height, std::vector<std::uint8_t>& rgb,
                  std::string& why) {
    if (jpeg.size() < 4 || jpeg[0] != 0xFF || jpeg[1] != 0xD8) {
        why = "not a JPEG frame";
        return false;
    }
    rgb.resize(std::size_t(width) * std::size_t(height) * 3);
    JpegErrors errors;
    if (decode(jpeg.data(), static_cast<unsigned long>(jpeg.size()), width, height, rgb.data(), &errors) != 0) {
        why = errors.message;
        return false;
    }
    return true;
}

}  // namespace vkfuse

// The PNG decoder on arbitrary bytes: a consistent image or an Error(Format)
// naming the file; never a crash, an out-of-bounds access, a leak (ASan) or
// undefined behaviour (UBSan).
#include <string>
#include <vector>

#include "fuzz_image.hpp"
#include "fuzz_targets.hpp"
#include "io/png.hpp"

namespace vkfuse::fuzz {

int png(const std::uint8_t* data, std::size_t size) {
    const std::vector<unsigned char> bytes(data, data + size);
    decode_checked("fuzz.png", [&] { return io::decode_png(bytes, "fuzz.png"); });
    return 0;
}

}  // namespace vkfuse::fuzz

VKFUSE_FUZZ_ENTRY(vkfuse::fuzz::png)

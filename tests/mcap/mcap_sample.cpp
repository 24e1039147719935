// Writes the sample MCAP file (mcap_sample.hpp) and prints the lines an
// independent reader must give back (tests/mcap/check_mcap.sh); or, with
// --dataset, a small recording of two 6x4 sensors through DatasetWriter (the
// seeds of fuzz/corpus/mcap).
//
//   vkfuse_mcap_sample OUT.mcap CHUNK_BYTES [none|zstd|lz4]
//   vkfuse_mcap_sample --dataset OUT.mcap none|zstd|lz4
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "mcap_sample.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace {

void write_dataset(const char* path, const char* compression) {
    using namespace vkfuse;
    DatasetWriter w(path, "vkfuse_mcap_sample", {compression});
    for (const char* serial : {"A-1", "B-2"}) w.add_sensor({"test", serial, 6, 4, 60.0, LedLayout::digit()});
    const IlluminationSequence sequence{Illumination::parse("15,15,15"), Illumination::parse("0,15,0")};
    w.set_run({sequence, FusionSpec{}, 1});
    std::uint64_t index = 0;
    auto frame = [&](int seed) {
        Frame f;
        f.index = index++;
        f.timestamp = 0.1 + double(f.index) / 60.0;
        f.height = 4;
        f.width = 6;
        f.pixels.resize(6 * 4 * 3);
        for (std::size_t i = 0; i < f.pixels.size(); ++i) f.pixels[i] = std::uint8_t(i * 37 + std::size_t(seed) * 11);
        return f;
    };
    for (int s = 0; s < 2; ++s)
        for (const Illumination& lit : sequence) w.add_frame(s, "nothing", true, frame(s), lit);
    for (int c = 0; c < 3; ++c)
        for (int s = 0; s < 2; ++s) {
            if (s == 1 && c == 1) {
                w.add_miss(1, {1, "timeout", "B-2: no frame within 5 s"});
                continue;
            }
            for (const Illumination& lit : sequence) w.add_frame(s, "coin", false, frame(c + s), lit, c);
        }
    w.finish();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 4 && std::strcmp(argv[1], "--dataset") == 0) {
        try {
            write_dataset(argv[2], argv[3]);
        } catch (const vkfuse::Error& e) {
            std::fprintf(stderr, "%s\n", e.what());
            return 1;
        }
        return 0;
    }
    if (argc != 3 && argc != 4) {
        std::fprintf(stderr, "usage: vkfuse_mcap_sample OUT.mcap CHUNK_BYTES [none|zstd|lz4]\n"
                             "       vkfuse_mcap_sample --dataset OUT.mcap none|zstd|lz4\n");
        return 2;
    }
    const auto compression = vkfuse::io::mcap::parse_compression_option(argc == 4 ? argv[3] : "none");
    if (!compression) {
        std::fprintf(stderr, "vkfuse_mcap_sample: compression %s (expected none, zstd or lz4)\n", argv[3]);
        return 2;
    }
    std::FILE* f = std::fopen(argv[1], "wb");
    if (!f) {
        std::perror(argv[1]);
        return 1;
    }
    try {
        vkfuse::io::mcap::Writer w(f, argv[1],
                                   {"ros2", "vkfuse tests", std::size_t(std::strtoull(argv[2], nullptr, 10)), *compression});
        vkfuse::test::write_sample(w);
    } catch (const vkfuse::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    if (std::fclose(f) != 0) return 1;
    std::fputs(vkfuse::test::sample_lines().c_str(), stdout);
    return 0;
}

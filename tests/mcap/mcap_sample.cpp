// Writes the sample MCAP file (mcap_sample.hpp) and prints the lines an
// independent reader must give back (tests/mcap/check_mcap.sh).
//
//   vkfuse_mcap_sample OUT.mcap CHUNK_BYTES
#include <cstdio>
#include <cstdlib>

#include "mcap_sample.hpp"
#include "vkfuse/core/error.hpp"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: vkfuse_mcap_sample OUT.mcap CHUNK_BYTES\n");
        return 2;
    }
    std::FILE* f = std::fopen(argv[1], "wb");
    if (!f) {
        std::perror(argv[1]);
        return 1;
    }
    try {
        vkfuse::io::mcap::Writer w(f, argv[1], {"ros2", "vkfuse tests", std::size_t(std::strtoull(argv[2], nullptr, 10))});
        vkfuse::test::write_sample(w);
    } catch (const vkfuse::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    if (std::fclose(f) != 0) return 1;
    std::fputs(vkfuse::test::sample_lines().c_str(), stdout);
    return 0;
}

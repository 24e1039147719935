// Replays every committed fuzz input - the seed corpora and each input that
// once broke a target (regressions/) - through the fuzz entry points, built
// without libFuzzer, as part of the normal test run. A target aborts on a
// broken contract, which fails this test; the file being replayed is printed
// first so the log names it.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"
#include "io/npy.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::fuzz {
namespace {

std::vector<std::filesystem::path> inputs_of(const std::string& target) {
    std::vector<std::filesystem::path> files;
    for (const char* kind : {"corpus", "regressions"}) {
        const std::filesystem::path dir = std::filesystem::path(VKFUSE_FUZZ_DIR) / kind / target;
        if (!std::filesystem::exists(dir)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(dir))
            if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::size_t replay(const std::string& target, int (*entry)(const std::uint8_t*, std::size_t)) {
    const std::vector<std::filesystem::path> files = inputs_of(target);
    for (const auto& path : files) {
        std::printf("replaying %s\n", path.c_str());
        std::fflush(stdout);
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        EXPECT_EQ(entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), 0) << path;
    }
    return files.size();
}

// decode_npy (what fuzz_npy exercises) and the file reader (what every
// command uses) are two readers of one format: they must take and refuse the
// same files, each committed input, each of its truncations and each with a
// byte too many, and agree on what they take to the bit.
TEST(FuzzReplay, NpyDecoderAgreesWithTheFileReader) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("vkfuse_npy_agreement_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "input.npy").string();
    std::size_t compared = 0, taken = 0;
    const auto compare = [&](const std::string& bytes, const std::string& about) {
        {
            std::ofstream out(path, std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), std::streamsize(bytes.size()));
        }
        std::optional<Image> decoded, read;
        std::string decode_error, read_error;
        try {
            decoded = io::decode_npy(std::vector<unsigned char>(bytes.begin(), bytes.end()), path);
        } catch (const Error& e) {
            decode_error = e.what();
        }
        try {
            read = io::read_image(path);
        } catch (const Error& e) {
            read_error = e.what();
        }
        ++compared;
        ASSERT_EQ(decoded.has_value(), read.has_value())
            << about << ": decode_npy " << (decoded ? "took it" : decode_error) << ", the file reader "
            << (read ? "took it" : read_error);
        if (!decoded) return;
        ++taken;
        EXPECT_TRUE(decoded->height == read->height && decoded->width == read->width &&
                    decoded->channels == read->channels && decoded->data == read->data)
            << about << ": the two readers decode different images";
    };
    for (const auto& file : inputs_of("npy")) {
        std::ifstream in(file, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        compare(bytes, file.string());
        for (std::size_t n = 0; n < bytes.size(); ++n) compare(bytes.substr(0, n), file.string() + " cut to " + std::to_string(n));
        compare(bytes + '\0', file.string() + " with a byte more");
    }
    std::filesystem::remove_all(dir);
    EXPECT_GE(taken, 5u) << "of " << compared;
}

// Each target has a seed corpus; an empty one would mean the path is wrong.
TEST(FuzzReplay, Png) { EXPECT_GE(replay("png", png), 5u); }
TEST(FuzzReplay, Npy) { EXPECT_GE(replay("npy", npy), 5u); }
TEST(FuzzReplay, Args) { EXPECT_GE(replay("args", args), 5u); }
TEST(FuzzReplay, Mcap) { EXPECT_GE(replay("mcap", mcap), 3u); }
TEST(FuzzReplay, WebSocketMessages) { EXPECT_GE(replay("ws", ws), 5u); }

}  // namespace
}  // namespace vkfuse::fuzz

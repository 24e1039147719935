// Every kind of bad input: exit status 2, exactly one line on stderr that
// names the input and the problem, nothing on stdout, no file created.
#include <gtest/gtest.h>

#include <limits>

#include "cli_runner.hpp"
#include "test_support.hpp"
#include "vkfuse/io.hpp"

namespace vkfuse::test {
namespace {

struct BadRun {
    std::string name;
    std::vector<std::string> args;  // "@x" stands for the file x in the test's directory
    std::string fragment;           // what the stderr line must contain ("@x" expanded too)
};

// A directory of inputs: three 16x16 RGB frames, a smaller one, a gray one, a
// tiny one, a NaN one, a corrupt PNG and a directory named like an image.
void write_inputs(const TempDir& dir) {
    for (std::string name : {"a", "b", "c"})
        io::write_image(dir.file(name + ".npy"), convert<float>(random_image(16, 16, 3, name[0])));
    io::write_image(dir.file("small.npy"), Image(8, 8, 3));
    io::write_image(dir.file("gray.npy"), Image(16, 16, 1));
    io::write_image(dir.file("tiny.npy"), Image(4, 4, 3));
    Image nan(16, 16, 3);
    nan.at(3, 5, 1) = std::numeric_limits<float>::quiet_NaN();
    io::write_image(dir.file("nan.npy"), nan);
    write_bytes(dir.file("bad.png"), "GIF89a, not a PNG");
    std::filesystem::create_directory(dir.file("folder.npy"));
}

std::string expand(const TempDir& dir, const std::string& word) {
    std::string out = word;
    for (std::size_t at; (at = out.find('@')) != std::string::npos;) {
        std::size_t end = out.find_first_of(" '", at);
        if (end == std::string::npos) end = out.size();
        out.replace(at, end - at, dir.file(out.substr(at + 1, end - at - 1)));
    }
    return out;
}

std::vector<BadRun> bad_runs() {
    const std::vector<std::string> fuse{"fuse", "--backend", "cpu", "-o", "@out.npy"};
    auto with = [&](std::vector<std::string> base, std::vector<std::string> more) {
        base.insert(base.end(), more.begin(), more.end());
        return base;
    };
    return {
        {"missing_file", with(fuse, {"--method", "brovey", "@a.npy", "@absent.npy"}),
         "@absent.npy: cannot open: No such file or directory"},
        {"directory_input", with(fuse, {"--method", "brovey", "@a.npy", "@folder.npy"}), "@folder.npy: not a regular file"},
        {"corrupt_png", with(fuse, {"--method", "brovey", "@bad.png", "@a.npy"}), "@bad.png: not a PNG file"},
        {"nan_npy", with(fuse, {"--method", "brovey", "@a.npy", "@nan.npy"}), "@nan.npy: NaN at row 3, column 5, channel 1"},
        {"mismatched_shapes", with(fuse, {"--method", "brovey", "@a.npy", "@b.npy", "@small.npy"}),
         "@small.npy: shape 8x8x3 differs from @a.npy's 16x16x3"},
        {"mismatched_channels", with(fuse, {"--method", "brovey", "@gray.npy", "@a.npy"}),
         "@a.npy: shape 16x16x3 differs from @gray.npy's 16x16x1"},
        {"unknown_method", with(fuse, {"--method", "median", "@a.npy", "@b.npy"}), "--method: unknown method \"median\""},
        {"unknown_wavelet", with(fuse, {"--method", "wavelet", "--wavelet", "db9", "@a.npy", "@b.npy"}), "\"db9\""},
        {"unknown_mode", with(fuse, {"--method", "wavelet", "--mode", "zero", "@a.npy", "@b.npy"}), "--mode"},
        {"unknown_base_rule", with(fuse, {"--method", "laplacian", "--base-rule", "sum", "@a.npy"}), "--base-rule"},
        {"unknown_detail_rule", with(fuse, {"--method", "laplacian", "--detail-rule", "x", "@a.npy"}), "--detail-rule"},
        {"impossible_levels", with(fuse, {"--method", "wavelet", "--wavelet", "haar", "--levels", "9", "@a.npy", "@b.npy"}),
         "--levels 9: a 16x16 image carries at most 4 levels of haar"},
        {"too_small_for_default", with(fuse, {"--method", "wavelet", "@tiny.npy", "@tiny.npy"}), "--levels"},
        {"channel_sum_two_inputs", with(fuse, {"--method", "channel-sum", "@a.npy", "@b.npy"}), "channel-sum"},
        {"channel_sum_gray", with(fuse, {"--method", "channel-sum", "@gray.npy", "@gray.npy", "@gray.npy"}),
         "channel-sum"},
        {"unwritable_output",
         {"fuse", "--backend", "cpu", "--method", "brovey", "-o", "@nowhere/out.npy", "@a.npy", "@b.npy"},
         "@nowhere/out.npy: cannot create a file in its directory"},
        {"unknown_output_format",
         {"fuse", "--backend", "cpu", "--method", "brovey", "-o", "@out.jpg", "@a.npy", "@b.npy"},
         "@out.jpg: unknown image format '.jpg'"},
        {"no_inputs", with(fuse, {"--method", "brovey"}), "fuse: no input images"},
        {"no_output", {"fuse", "--method", "brovey", "@a.npy"}, "missing -o OUT"},
        {"no_method", {"fuse", "-o", "@out.npy", "@a.npy"}, "missing --method M"},
        {"unknown_option", with(fuse, {"--method", "brovey", "--fast", "@a.npy"}), "fuse: unknown option --fast"},
        {"missing_value", with(fuse, {"@a.npy", "--method"}), "option --method needs a value"},
        {"levels_not_a_number", with(fuse, {"--method", "laplacian", "--levels", "abc", "@a.npy"}),
         "--levels abc: expected a positive integer"},
        {"levels_negative", with(fuse, {"--method", "laplacian", "--levels", "-1", "@a.npy"}),
         "--levels -1: expected a positive integer"},
        {"levels_trailing_junk", with(fuse, {"--method", "laplacian", "--levels=3x", "@a.npy"}), "--levels 3x"},
        {"unknown_backend", {"fuse", "--backend", "gpu", "--method", "brovey", "-o", "@out.npy", "@a.npy"},
         "--backend gpu: expected cpu, vulkan or auto"},
        {"unknown_command", {"frobnicate"}, "unknown command 'frobnicate'"},
        {"no_command", {}, "missing command"},
        {"metrics_no_inputs", {"metrics", "--backend", "cpu"}, "metrics: no input images"},
        {"metrics_missing_file", {"metrics", "--backend", "cpu", "@a.npy", "@absent.png"}, "@absent.png: cannot open"},
        {"metrics_nan", {"metrics", "--backend", "cpu", "@nan.npy"}, "@nan.npy: NaN at row 3"},
        {"metrics_missing_background", {"metrics", "--backend", "cpu", "--background", "@absent.npy", "@a.npy"},
         "@absent.npy: cannot open"},
        {"metrics_background_shape", {"metrics", "--backend", "cpu", "--background", "@small.npy", "@a.npy"},
         "@a.npy: shape 16x16x3 differs from the background @small.npy's 8x8x3"},
        {"metrics_unknown_option", {"metrics", "-o", "x.npy", "@a.npy"}, "metrics: unknown option -o"},
        {"info_operand", {"info", "extra"}, "info: unexpected operand extra"},
    };
}

class CliErrors : public ::testing::TestWithParam<BadRun> {};

TEST_P(CliErrors, ExitTwoWithOneLineAndNoOutputFile) {
    const BadRun& bad = GetParam();
    TempDir dir;
    write_inputs(dir);
    std::vector<std::string> before = dir.entries();
    std::vector<std::string> args;
    for (const std::string& a : bad.args) args.push_back(expand(dir, a));
    CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.out, "");
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("vkfuse: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(expand(dir, bad.fragment)), std::string::npos) << r.err;
    EXPECT_EQ(dir.entries(), before);  // no output, no temporary
}

INSTANTIATE_TEST_SUITE_P(BadInput, CliErrors, ::testing::ValuesIn(bad_runs()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace vkfuse::test

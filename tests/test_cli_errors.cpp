// Every kind of bad input: exit status 2, exactly one line on stderr that
// names the input and the problem, nothing on stdout, no file created.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <limits>

#include "cli_runner.hpp"
#include "npy_bytes.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

struct BadRun {
    std::string name;
    std::vector<std::string> args;  // "@x" stands for the file x in the test's directory
    std::string fragment;           // what the stderr line must contain ("@x" expanded too)
};

// Image files broken in every way a reader can meet: empty, cut short,
// corrupt, unsupported dtype or shape, non-finite values, and a FIFO (which
// must be refused at once, not waited on for a writer).
void write_broken_files(const TempDir& dir) {
    write_bytes(dir.file("empty.png"), "");
    write_bytes(dir.file("empty.npy"), "");
    io::write_image(dir.file("whole.png"), convert<float>(random_image(16, 16, 3, 9)));
    const std::string png = read_bytes(dir.file("whole.png"));
    write_bytes(dir.file("cut.png"), png.substr(0, png.size() / 2));
    std::filesystem::remove(dir.file("whole.png"));
    const std::string f4_16x16(16 * 16 * 4, '\0');
    write_bytes(dir.file("cut.npy"), npy_bytes(dict_of("<f4", false, "(16, 16)"), f4_16x16.substr(0, 100)));
    write_bytes(dir.file("junk.npy"), "PK\x03\x04 a zip archive, not an array");
    write_bytes(dir.file("int.npy"), npy_bytes(dict_of("<i4", false, "(16, 16)"), f4_16x16));
    write_bytes(dir.file("rank1.npy"), npy_bytes(dict_of("<f4", false, "(256,)"), f4_16x16.substr(0, 1024)));
    write_bytes(dir.file("twochan.npy"), npy_bytes(dict_of("<f4", false, "(16, 8, 2)"), f4_16x16.substr(0, 1024)));
    write_bytes(dir.file("big.npy"), npy_bytes(dict_of("<f8", false, "(1, 1)"), std::string("\x00\x00\x00\x00\x00\x00\xf0\x7f", 8)));
    Image inf(16, 16, 3);
    inf.at(2, 4, 0) = std::numeric_limits<float>::infinity();
    io::write_image(dir.file("inf.npy"), inf);
    inf.at(2, 4, 0) = 0;
    inf.at(15, 0, 2) = -std::numeric_limits<float>::infinity();
    io::write_image(dir.file("ninf.npy"), inf);
    if (::mkfifo(dir.file("fifo.npy").c_str(), 0644) != 0) throw std::runtime_error("mkfifo failed");
}

// A directory of inputs: three 16x16 RGB frames, a smaller one, a gray one, a
// tiny one, a NaN one, a corrupt PNG, a directory named like an image and the
// broken files above.
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
    write_broken_files(dir);
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
        {"empty_png", with(fuse, {"--method", "brovey", "@empty.png", "@a.npy"}), "@empty.png: empty file"},
        {"empty_npy", with(fuse, {"--method", "brovey", "@a.npy", "@empty.npy"}), "@empty.npy: empty file"},
        {"truncated_png", with(fuse, {"--method", "brovey", "@a.npy", "@cut.png"}), "@cut.png: corrupt PNG"},
        {"truncated_npy", with(fuse, {"--method", "brovey", "@a.npy", "@cut.npy"}), "@cut.npy: truncated"},
        {"corrupt_npy", with(fuse, {"--method", "brovey", "@a.npy", "@junk.npy"}), "@junk.npy: not a .npy file"},
        {"unsupported_dtype", with(fuse, {"--method", "brovey", "@a.npy", "@int.npy"}),
         "@int.npy: unsupported dtype '<i4'"},
        {"unsupported_rank", with(fuse, {"--method", "brovey", "@a.npy", "@rank1.npy"}),
         "@rank1.npy: unsupported shape 256"},
        {"unsupported_channels", with(fuse, {"--method", "brovey", "@a.npy", "@twochan.npy"}),
         "@twochan.npy: unsupported shape 16x8x2"},
        {"inf_npy", with(fuse, {"--method", "brovey", "@a.npy", "@inf.npy"}), "@inf.npy: Inf at row 2, column 4, channel 0"},
        {"negative_inf_npy", with(fuse, {"--method", "laplacian", "@ninf.npy"}),
         "@ninf.npy: -Inf at row 15, column 0, channel 2"},
        {"float64_beyond_float32", with(fuse, {"--method", "brovey", "@big.npy"}), "@big.npy: Inf at row 0, column 0"},
        {"fifo_input", with(fuse, {"--method", "brovey", "@a.npy", "@fifo.npy"}), "@fifo.npy: not a regular file"},
        {"channel_sum_four_inputs", with(fuse, {"--method", "channel-sum", "@a.npy", "@b.npy", "@c.npy", "@a.npy"}),
         "--method channel-sum: needs exactly 3 frames (red, green, blue LED), got 4"},
        {"laplacian_absurd_levels", with(fuse, {"--method", "laplacian", "--levels", "2147483647", "@a.npy"}),
         "--levels 2147483647: a Laplacian pyramid takes at most 32 levels"},
        {"levels_zero", with(fuse, {"--method", "laplacian", "--levels", "0", "@a.npy"}),
         "--levels 0: expected a positive integer"},
        {"levels_beyond_int", with(fuse, {"--method", "wavelet", "--levels", "99999999999", "@a.npy", "@b.npy"}),
         "--levels 99999999999: expected a positive integer"},
        {"output_is_a_directory",
         {"fuse", "--backend", "cpu", "--method", "brovey", "-o", "@folder.npy", "@a.npy", "@b.npy"},
         "@folder.npy: cannot replace: Is a directory"},
        {"output_below_a_file",
         {"fuse", "--backend", "cpu", "--method", "brovey", "-o", "@a.npy/out.npy", "@a.npy", "@b.npy"},
         "@a.npy/out.npy: cannot create a file in its directory: Not a directory"},
        {"metrics_empty_png", {"metrics", "--backend", "cpu", "@empty.png"}, "@empty.png: empty file"},
        {"metrics_truncated_npy", {"metrics", "--backend", "cpu", "@a.npy", "@cut.npy"}, "@cut.npy: truncated"},
        {"metrics_fifo", {"metrics", "--backend", "cpu", "@fifo.npy"}, "@fifo.npy: not a regular file"},
        {"metrics_inf_background", {"metrics", "--backend", "cpu", "--background", "@inf.npy", "@a.npy"},
         "@inf.npy: Inf at row 2"},
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

// A failed run leaves an existing output file exactly as it was: the result
// is written to a temporary beside it and renamed only on success.
TEST(CliErrorsOutput, ExistingOutputSurvivesAFailedRunUnchanged) {
    TempDir dir;
    write_inputs(dir);
    write_bytes(dir.file("out.npy"), "the previous result");
    CliResult r = run_cli({"fuse", "--backend", "cpu", "--method", "brovey", "-o", dir.file("out.npy"),
                           dir.file("a.npy"), dir.file("cut.npy")});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(read_bytes(dir.file("out.npy")), "the previous result");
}

// chmod 000 stops every user but root, and the tests often run as root
// (CI containers): there the case cannot be made, and the test says so.
TEST(CliErrorsOutput, UnreadableInputNamesThePermission) {
    if (::geteuid() == 0) GTEST_SKIP() << "running as root: permission bits do not stop root from reading";
    TempDir dir;
    write_inputs(dir);
    ASSERT_EQ(::chmod(dir.file("b.npy").c_str(), 0), 0);
    CliResult r = run_cli({"fuse", "--backend", "cpu", "--method", "brovey", "-o", dir.file("out.npy"),
                           dir.file("a.npy"), dir.file("b.npy")});
    EXPECT_EQ(r.status, 2);
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_NE(r.err.find(dir.file("b.npy") + ": cannot open: Permission denied"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.npy")));
}

}  // namespace
}  // namespace vkfuse::test

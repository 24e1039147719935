// `vkfuse metrics --backend cpu` end to end: one JSON line per input, equal to
// metrics_reference of the image read, and nothing printed when any input is bad.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "cli_runner.hpp"
#include "test_support.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::test {
namespace {

// The number after "key": in one JSON line, or nullopt when the key is absent.
std::optional<double> json_field(const std::string& line, const std::string& key) {
    std::size_t at = line.find("\"" + key + "\": ");
    if (at == std::string::npos) return std::nullopt;
    const char* start = line.c_str() + at + key.size() + 4;
    char* end = nullptr;
    double v = std::strtod(start, &end);
    if (end == start) return std::nullopt;
    return v;
}

void expect_relative(double got, double want, double tolerance, const std::string& what) {
    EXPECT_LE(std::abs(got - want), tolerance * std::max(std::abs(want), 1e-300)) << what << ": " << got << " vs " << want;
}

// Checks one printed line against metrics_reference of the file it names.
void expect_line_matches(const std::string& line, const std::string& path, const std::string& background,
                         double tolerance) {
    ImageD img = convert<double>(io::read_image(path));
    std::optional<ImageD> bg;
    if (!background.empty()) bg = convert<double>(io::read_image(background));
    Metrics want = metrics_reference(img, bg ? &*bg : nullptr);
    EXPECT_EQ(line.rfind("{\"image\": \"" + path + "\", \"sharpness\": ", 0), 0u) << line;
    EXPECT_EQ(line.back(), '}') << line;
    ASSERT_TRUE(json_field(line, "sharpness") && json_field(line, "contrast")) << line;
    expect_relative(*json_field(line, "sharpness"), want.sharpness, tolerance, path + " sharpness");
    expect_relative(*json_field(line, "contrast"), want.contrast, tolerance, path + " contrast");
    EXPECT_EQ(json_field(line, "background_diff").has_value(), bg.has_value()) << line;
    if (bg) expect_relative(*json_field(line, "background_diff"), *want.background_diff, tolerance, path + " D");
}

// Three inputs of two shapes, gray and RGB, .npy and PNG.
std::vector<std::string> write_inputs(const TempDir& dir) {
    std::vector<std::string> paths{dir.file("a.npy"), dir.file("b.png"), dir.file("c.npy")};
    io::write_image(paths[0], convert<float>(structured_image(33, 41, 3, 1)));
    io::write_image(paths[1], convert<float>(structured_image(33, 41, 3, 2)));
    io::write_image(paths[2], convert<float>(random_image(17, 9, 1, 3)));
    return paths;
}

TEST(CliMetrics, CpuBackendPrintsTheReferenceMetricsInOrder) {
    TempDir dir;
    std::vector<std::string> paths = write_inputs(dir);
    CliResult r = run_cli({"metrics", "--backend", "cpu", paths[0], paths[1], paths[2]});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 3u) << r.out;
    for (std::size_t i = 0; i < 3; ++i) expect_line_matches(lines[i], paths[i], "", 1e-9);
}

TEST(CliMetrics, BackgroundDifferenceOnlyWithBackground) {
    TempDir dir;
    std::vector<std::string> paths = write_inputs(dir);
    std::string bg = test::data_path("digit_bg_tacto.png");
    std::string frame = dir.file("frame.npy");
    Image touched = io::read_image(bg);
    for (int y = 100; y < 140; ++y)
        for (int x = 80; x < 130; ++x) touched.at(y, x, 1) *= 0.5f;  // a contact patch
    io::write_image(frame, touched);
    CliResult r = run_cli({"metrics", "--background", bg, "--backend", "cpu", frame, bg});
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 2u) << r.out;
    expect_line_matches(lines[0], frame, bg, 1e-9);
    expect_line_matches(lines[1], bg, bg, 1e-9);
    EXPECT_GT(*json_field(lines[0], "background_diff"), 0.0);
    EXPECT_EQ(*json_field(lines[1], "background_diff"), 0.0);
}

TEST(CliMetrics, NumbersCarryFullPrecisionAndPathsAreEscaped) {
    TempDir dir;
    std::string path = dir.file("we\"ird\\name.npy");
    io::write_image(path, convert<float>(random_image(5, 6, 3, 9)));
    CliResult r = run_cli({"metrics", "--backend", "cpu", path});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("we\\\"ird\\\\name.npy\""), std::string::npos) << r.out;
    Metrics want = metrics_reference(convert<double>(io::read_image(path)));
    EXPECT_EQ(*json_field(r.out, "sharpness"), want.sharpness);  // %.17g round-trips exactly
    EXPECT_EQ(*json_field(r.out, "contrast"), want.contrast);
}

TEST(CliMetrics, ABadInputPrintsNothingToStdout) {
    TempDir dir;
    std::vector<std::string> paths = write_inputs(dir);
    write_bytes(dir.file("broken.png"), "\x89PNG\r\n\x1a\n but then nothing");
    CliResult r = run_cli({"metrics", "--backend", "cpu", paths[0], paths[1], dir.file("broken.png")});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("vkfuse: " + dir.file("broken.png") + ": ", 0), 0u) << r.err;
}

TEST(CliMetrics, BackgroundOfAnotherShapeIsAnErrorBeforeAnyOutput) {
    TempDir dir;
    std::vector<std::string> paths = write_inputs(dir);
    CliResult r = run_cli({"metrics", "--backend", "cpu", "--background", paths[0], paths[1], paths[2]});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_EQ(r.err, "vkfuse: " + paths[2] + ": shape 17x9x1 differs from the background " + paths[0] +
                         "'s 33x41x3\n");
}

}  // namespace
}  // namespace vkfuse::test

// ImageWriteQueue (tools/run/image_write_queue.hpp): `vkfuse run` writes its fused
// PNGs on a thread of their own; every image lands, in order, and a failed
// write fails the run instead of vanishing on the other thread.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <memory>

#include "run/image_write_queue.hpp"
#include "temp_dir.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {
namespace {

Image ramp(int seed) {
    Image img(6, 5, 3);
    for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = float((i * 7 + std::size_t(seed) * 13) % 256) / 255.0f;
    return img;
}

TEST(ImageWriteQueue, WritesEveryImageEvenWithATinyBudget) {
    TempDir tmp;
    // A budget below one image: each push waits for the one before, none is lost.
    cli::ImageWriteQueue queue(1);
    for (int i = 0; i < 8; ++i) queue.push_png(tmp.file(std::to_string(i) + ".png"), std::make_shared<const Image>(ramp(i)));
    queue.drain();
    for (int i = 0; i < 8; ++i) {
        const Image back = io::read_image(tmp.file(std::to_string(i) + ".png"));
        const Image want = ramp(i);
        ASSERT_EQ(back.data.size(), want.data.size());
        for (std::size_t k = 0; k < want.data.size(); ++k) ASSERT_NEAR(back.data[k], want.data[k], 0.5f / 255.0f) << i;
    }
}

TEST(ImageWriteQueue, AFailedWriteFailsDrainAndLaterPushes) {
    TempDir tmp;
    cli::ImageWriteQueue queue(std::size_t(1) << 20);
    const std::string bad = tmp.file("missing-directory/0.png");
    queue.push_png(bad, std::make_shared<const Image>(ramp(0)));
    try {
        queue.drain();
        FAIL() << "drain() did not report the failed write";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
    EXPECT_THROW(queue.push_png(tmp.file("1.png"), std::make_shared<const Image>(ramp(1))), Error);
}

TEST(ImageWriteQueue, DestroyingWithImagesWaitingReturns) {
    TempDir tmp;
    {
        cli::ImageWriteQueue queue(std::size_t(1) << 30);
        for (int i = 0; i < 64; ++i) queue.push_png(tmp.file(std::to_string(i) + ".png"), std::make_shared<const Image>(ramp(i)));
    }  // returns at once: what was not written yet is dropped
    // What was written is whole: every entry a readable PNG, no temporary left.
    for (const std::string& name : tmp.entries()) {
        ASSERT_EQ(name.substr(name.size() - 4), ".png") << name;
        EXPECT_NO_THROW(io::read_image(tmp.file(name))) << name;
    }
}

// An image an earlier file holds is a second name for that file (same inode),
// written after it in queue order; a name already taken is never replaced.
TEST(ImageWriteQueue, ALinkNamesTheEarlierFileAndNeverReplacesOne) {
    TempDir tmp;
    {
        cli::ImageWriteQueue queue(1);
        queue.push_png(tmp.file("0.png"), std::make_shared<const Image>(ramp(3)));
        queue.push_link(tmp.file("1.png"), tmp.file("0.png"));
        queue.drain();
    }
    struct stat a {}, b {};
    ASSERT_EQ(::stat(tmp.file("0.png").c_str(), &a), 0);
    ASSERT_EQ(::stat(tmp.file("1.png").c_str(), &b), 0);
    EXPECT_EQ(a.st_ino, b.st_ino);
    EXPECT_EQ(io::read_image(tmp.file("1.png")).data, io::read_image(tmp.file("0.png")).data);

    write_bytes(tmp.file("taken.png"), "not ours");
    try {
        cli::add_file_name(tmp.file("0.png"), tmp.file("taken.png"));
        FAIL() << "an existing file was replaced";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("taken.png"), std::string::npos) << e.what();
    }
    EXPECT_EQ(read_bytes(tmp.file("taken.png")), "not ours");
}

}  // namespace
}  // namespace vkfuse::test

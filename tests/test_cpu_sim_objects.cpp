// What the simulated DIGIT can be pressed with: every object shows.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_support.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse {
namespace {

const Illumination kWhite({15, 15, 15});

ImageD settled_frame(SimDigit& sim) { return test::to_image(test::settle(sim, kWhite)); }

double background_diff(const ImageD& img, const ImageD& background) {
    return *metrics_reference(img, &background).background_diff;
}

// Centre of mass of |frame - background| (x, y in pixels).
std::array<double, 2> contact_centre(const ImageD& img, const ImageD& background) {
    double sx = 0, sy = 0, s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            double d = 0;
            for (int c = 0; c < 3; ++c) d += std::abs(img.at(y, x, c) - background.at(y, x, c));
            sx += d * x;
            sy += d * y;
            s += d;
        }
    return {sx / s, sy / s};
}

TEST(SimObjects, TheCatalogueHasNothingAndNineObjects) {
    const auto names = SimDigit::objects();
    EXPECT_EQ(names, (std::vector<std::string>{"nothing", "coin-heads", "coin-tails", "lego", "ball", "screw", "nut",
                                               "velcro", "file", "text"}));
}

TEST(SimObjects, EveryObjectShowsAndNothingIsTheBackground) {
    SimDigitOptions o;
    o.object = "nothing";
    SimDigit sim(o);
    const ImageD background = settled_frame(sim);
    o.seed = 99;
    SimDigit other(o);
    const ImageD again = settled_frame(other);
    // "nothing" is the background: the same statistics, differing by noise only.
    const double noise_only = background_diff(again, background);
    EXPECT_LT(noise_only, 1.5 / 255);
    const auto m0 = test::channel_means(background), m1 = test::channel_means(again);
    for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(m0[c], m1[c], 0.05);
    const Metrics b0 = metrics_reference(background), b1 = metrics_reference(again);
    EXPECT_NEAR(b0.contrast, b1.contrast, 1e-3);
    EXPECT_NEAR(b0.sharpness, b1.sharpness, 2e-4);

    for (const std::string& name : SimDigit::objects()) {
        if (name == "nothing") continue;
        sim.set_object(name, 1.0);
        const double d = background_diff(settled_frame(sim), background);
        // Well above the noise floor (about 1.3 DN): at least 4 DN averaged over
        // the whole frame, most of which the contact does not cover.
        EXPECT_GT(d, std::max(3 * noise_only, 4.0 / 255)) << name;
    }
}

TEST(SimObjects, AliasCoinIsTheHeadsSide) {
    SimDigitOptions o;
    o.object = "coin";
    const Frame a = SimDigit(o).grab();
    o.object = "coin-heads";
    EXPECT_EQ(SimDigit(o).grab().pixels, a.pixels);
}

TEST(SimObjects, PressingHarderShowsMore) {
    SimDigitOptions o;
    o.object = "nothing";
    SimDigit sim(o);
    const ImageD background = settled_frame(sim);
    double previous = 0;
    for (double depth : {0.2, 0.6, 1.2}) {
        sim.set_object("ball", depth);
        const double d = background_diff(settled_frame(sim), background);
        EXPECT_GT(d, previous) << depth << " mm";
        previous = d;
    }
}

TEST(SimObjects, TheContactFollowsThePosition) {
    SimDigitOptions o;
    o.object = "nothing";
    o.camera_auto = false;  // keep the background's brightness out of the difference
    SimDigit sim(o);
    const ImageD background = settled_frame(sim);
    sim.set_object("ball", 0.8);
    for (auto [x, y] : {std::pair{0.3, 0.4}, std::pair{0.7, 0.6}}) {
        sim.move_object(x, y);
        const auto centre = contact_centre(settled_frame(sim), background);
        // Shading and shadows spread around the contact; its centre stays near.
        EXPECT_NEAR(centre[0], x * 320, 25) << x;
        EXPECT_NEAR(centre[1], y * 240, 25) << y;
    }
}

TEST(SimObjects, VgaRendersTheSameScene) {
    SimDigitOptions o;
    o.object = "coin-tails";
    o.camera_auto = false;
    const ImageD qvga = test::to_image(SimDigit(o).grab());
    o.vga = true;
    const ImageD vga = test::to_image(SimDigit(o).grab());
    // Halved, VGA is the QVGA frame but for noise and finer detail.
    ImageD half(240, 320, 3);
    for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x)
            for (int c = 0; c < 3; ++c)
                half.at(y, x, c) = 0.25 * (vga.at(2 * y, 2 * x, c) + vga.at(2 * y + 1, 2 * x, c) +
                                           vga.at(2 * y, 2 * x + 1, c) + vga.at(2 * y + 1, 2 * x + 1, c));
    for (int c = 0; c < 3; ++c) EXPECT_GT(test::correlation(test::block_means(half, c), test::block_means(qvga, c)), 0.98);
}

}  // namespace
}  // namespace vkfuse

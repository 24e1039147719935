// The study (vkfuse/study/study.hpp) on a small synthetic dataset: the device
// and the CPU reference agree on every figure, the analysis matches a recount
// made here from fuse_reference and metrics_reference, and bad datasets and
// options get one line each.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "expect_error.hpp"
#include "study_dataset.hpp"
#include "temp_dir.hpp"
#include "vk_fixture.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/study/study.hpp"

namespace vkfuse::test {
namespace {

StudyOptions small_options(int max_k) {
    StudyOptions o;
    o.max_k = max_k;
    o.greedy_max = 3;
    o.top = 3;
    return o;
}

const StudyMethod& method_named(const std::string& name) {
    static const std::vector<StudyMethod> methods = study_methods();
    for (const StudyMethod& m : methods)
        if (m.name == name) return m;
    throw std::runtime_error("no method " + name);
}

// The gains of one fusion, recounted here with the reference path.
struct Recount {
    const Dataset& dataset;
    std::vector<Illumination> grid;
    std::vector<std::string> objects;

    ImageD image(const std::string& object, const Illumination& s, bool background) const {
        for (const DatasetTake& t : dataset.sensors[0].takes)
            if (t.background == background && (background || t.object == object))
                for (const DatasetFrame& f : t.frames)
                    if (f.illumination == s) {
                        const Frame frame = load_frame(dataset, dataset.sensors[0], f);
                        ImageD img(frame.height, frame.width, 3);
                        for (std::size_t i = 0; i < img.size(); ++i) img.data[i] = frame.pixels[i] / 255.0;
                        if (!background) return img;
                        // The mean of the setting's background frames.
                        ImageD sum(frame.height, frame.width, 3);
                        int n = 0;
                        for (const DatasetFrame& g : t.frames)
                            if (g.illumination == s) {
                                const Frame bg = load_frame(dataset, dataset.sensors[0], g);
                                for (std::size_t i = 0; i < sum.size(); ++i) sum.data[i] += bg.pixels[i];
                                ++n;
                            }
                        for (double& v : sum.data) v /= 255.0 * n;
                        return sum;
                    }
        throw std::runtime_error("no frame");
    }

    Metrics metrics(const std::string& object, const std::vector<Illumination>& settings, const FusionSpec& spec) const {
        std::vector<ImageD> frames, backgrounds;
        for (const Illumination& s : settings) {
            frames.push_back(image(object, s, false));
            backgrounds.push_back(image(object, s, true));
        }
        const ImageD fused = settings.size() > 1 ? fuse_reference(frames, spec) : frames[0];
        const ImageD bg = settings.size() > 1 ? fuse_reference(backgrounds, spec) : backgrounds[0];
        return metrics_reference(fused, &bg);
    }

    Gains gains(const std::string& object, const std::vector<Illumination>& settings, const FusionSpec& spec) const {
        const Metrics m = metrics(object, settings, spec);
        const Metrics s = metrics(object, {Illumination({15, 15, 15})}, spec);
        return {m.sharpness / s.sharpness, m.contrast / s.contrast, *m.background_diff / *s.background_diff};
    }
};

void expect_close(const Gains& a, const Gains& b, double rel, const std::string& what) {
    EXPECT_NEAR(a.sharpness, b.sharpness, rel * std::abs(b.sharpness)) << what;
    EXPECT_NEAR(a.contrast, b.contrast, rel * std::abs(b.contrast)) << what;
    EXPECT_NEAR(a.background_diff, b.background_diff, rel * std::abs(b.background_diff)) << what;
}

class Study : public VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        dir_ = tmp_.file("set");
        write_study_dataset(dir_);
    }
    TempDir tmp_;
    std::string dir_;
};

TEST_F(Study, TheDeviceAgreesWithTheReferenceOnEveryFigure) {
    const Dataset d = read_dataset(dir_);
    const StudyResult cpu = run_study(d, small_options(2), nullptr);
    const StudyResult gpu = run_study(d, small_options(2), &ctx());
    EXPECT_EQ(cpu.backend, "cpu");
    EXPECT_EQ(gpu.backend.rfind("vulkan (", 0), 0u);
    ASSERT_EQ(cpu.methods.size(), gpu.methods.size());
    EXPECT_EQ(cpu.combinations, 8u + 28u);
    EXPECT_EQ(gpu.combinations, cpu.combinations);
    for (std::size_t m = 0; m < cpu.methods.size(); ++m) {
        const auto &c = cpu.methods[m], &g = gpu.methods[m];
        EXPECT_EQ(g.name, c.name);
        EXPECT_EQ(g.fusions, c.fusions);
        EXPECT_NEAR(g.improves_all_fraction, c.improves_all_fraction, 1.0 / 56 + 1e-12) << c.name;
        expect_close(g.mean_gain, c.mean_gain, 1e-4, c.name);
    }
    EXPECT_EQ(gpu.best_method, cpu.best_method);
    for (std::size_t i = 0; i < 3; ++i) {
        ASSERT_EQ(gpu.greedy[i].size(), cpu.greedy[i].size());
        for (std::size_t n = 0; n < cpu.greedy[i].size(); ++n) {
            EXPECT_EQ(gpu.greedy[i][n].sequence, cpu.greedy[i][n].sequence) << "metric " << i << " n " << n + 1;
            EXPECT_NEAR(gpu.greedy[i][n].value, cpu.greedy[i][n].value, 1e-4 * cpu.greedy[i][n].value);
        }
    }
    ASSERT_EQ(gpu.pairing.size(), 7u);
    for (std::size_t p = 0; p < cpu.pairing.size(); ++p)
        expect_close(gpu.pairing[p].gain, cpu.pairing[p].gain, 1e-4, "pairing " + std::to_string(p));
}

TEST_F(Study, TheAnalysisMatchesARecount) {
    const Dataset d = read_dataset(dir_);
    const StudyResult r = run_study(d, small_options(2), &ctx());
    const Recount recount{d, study_grid({}), {"ridge", "dots"}};
    ASSERT_EQ(r.settings, recount.grid);
    EXPECT_EQ(r.settings[r.static_setting], Illumination({15, 15, 15}));
    EXPECT_EQ(r.objects, recount.objects);
    // Brovey over every pair and object: the share improving all metrics and
    // the mean gains, from scratch.
    const StudyMethod& brovey = method_named("brovey");
    std::size_t improving = 0, n = 0;
    Gains sum;
    std::vector<std::pair<double, std::vector<std::size_t>>> by_sharpness;
    for (std::size_t a = 0; a < 8; ++a)
        for (std::size_t b = a + 1; b < 8; ++b) {
            double mean_sharpness = 0;
            for (const std::string& o : recount.objects) {
                const Gains g = recount.gains(o, {recount.grid[a], recount.grid[b]}, brovey.spec);
                improving += g.improves_all() ? 1 : 0;
                ++n;
                sum.sharpness += g.sharpness;
                sum.contrast += g.contrast;
                sum.background_diff += g.background_diff;
                mean_sharpness += g.sharpness / 2;
            }
            by_sharpness.push_back({mean_sharpness, {a, b}});
        }
    const auto it = std::find_if(r.methods.begin(), r.methods.end(), [](const auto& m) { return m.name == "brovey"; });
    ASSERT_NE(it, r.methods.end());
    EXPECT_EQ(it->fusions, 56u);
    EXPECT_NEAR(it->improves_all_fraction, double(improving) / double(n), 1.0 / 56 + 1e-12);
    expect_close(it->mean_gain, {sum.sharpness / n, sum.contrast / n, sum.background_diff / n}, 1e-4, "brovey");
    // Nothing takes channel-sum with combinations of two.
    const auto cs = std::find_if(r.methods.begin(), r.methods.end(), [](const auto& m) { return m.name == "channel-sum"; });
    ASSERT_NE(cs, r.methods.end());
    EXPECT_EQ(cs->fusions, 0u);
    // best_method has the highest share; the pairs are ranked by its gains.
    for (const auto& m : r.methods)
        EXPECT_LE(m.improves_all_fraction, std::find_if(r.methods.begin(), r.methods.end(), [&](const auto& x) {
                                               return x.name == r.best_method;
                                           })->improves_all_fraction);
    for (std::size_t i = 0; i < 3; ++i) {
        ASSERT_EQ(r.best_pairs[i].size(), 3u);
        for (std::size_t p = 1; p < 3; ++p)
            EXPECT_GE(r.best_pairs[i][p - 1].gain.of(kAllMetrics[i]), r.best_pairs[i][p].gain.of(kAllMetrics[i]));
    }
    if (r.best_method == "brovey") {
        std::stable_sort(by_sharpness.begin(), by_sharpness.end(),
                         [](const auto& x, const auto& y) { return x.first > y.first; });
        EXPECT_EQ(r.best_pairs[0][0].settings, by_sharpness[0].second);
    }
    // The greedy search starts from the best single frame, and each step
    // keeps the sequence before it.
    const FusionSpec any;
    for (std::size_t i = 0; i < 3; ++i) {
        double best = -1;
        std::size_t pick = 0;
        for (std::size_t s = 0; s < 8; ++s) {
            double mean = 0;
            for (const std::string& o : recount.objects) mean += recount.gains(o, {recount.grid[s]}, any).of(kAllMetrics[i]) / 2;
            if (mean > best) {
                best = mean;
                pick = s;
            }
        }
        ASSERT_EQ(r.greedy[i].size(), 3u);
        EXPECT_EQ(r.greedy[i][0].sequence, std::vector<std::size_t>{pick}) << "metric " << i;
        EXPECT_NEAR(r.greedy[i][0].value, best, 1e-5 * best);
        for (std::size_t step = 1; step < 3; ++step) {
            const auto& seq = r.greedy[i][step].sequence;
            ASSERT_EQ(seq.size(), step + 1);
            EXPECT_TRUE(std::equal(r.greedy[i][step - 1].sequence.begin(), r.greedy[i][step - 1].sequence.end(), seq.begin()));
        }
    }
    // The pairing of the static setting with (0,15,0), recounted.
    const std::size_t green = std::size_t(std::find(r.settings.begin(), r.settings.end(), Illumination({0, 15, 0})) -
                                          r.settings.begin());
    const auto pair = std::find_if(r.pairing.begin(), r.pairing.end(),
                                   [&](const auto& p) { return p.settings == std::vector<std::size_t>{green}; });
    ASSERT_NE(pair, r.pairing.end());
    const auto ranking = std::find_if(r.methods.begin(), r.methods.end(), [&](const auto& m) { return m.name == r.best_method; });
    if (ranking != r.methods.end() && r.best_method != "channel-sum") {
        Gains mean;
        for (const std::string& o : recount.objects) {
            const Gains g = recount.gains(o, {Illumination({0, 15, 0}), Illumination({15, 15, 15})},
                                          method_named(r.best_method).spec);
            mean.sharpness += g.sharpness / 2;
            mean.contrast += g.contrast / 2;
            mean.background_diff += g.background_diff / 2;
        }
        expect_close(pair->gain, mean, 1e-4, "(15,15,15) + (0,15,0)");
    }
    // Best overall: a scored pair, and when it improves everything on every
    // object, its gains all exceed 1.
    EXPECT_EQ(r.best.settings.size(), 2u);
    if (r.best_improves_all_objects) {
        EXPECT_TRUE(r.best.gain.improves_all());
    }
    for (std::size_t i = 0; i < 3; ++i) {
        ASSERT_EQ(r.best_k[i].size(), 2u);
        for (std::size_t k : r.best_k[i]) EXPECT_TRUE(k == 1 || k == 2);
    }
}

TEST_F(Study, ChannelSumTakesExactlyThreeSettings) {
    const Dataset d = read_dataset(dir_);
    StudyOptions o = small_options(3);
    o.objects = {"dots"};
    const StudyResult r = run_study(d, o, &ctx());
    EXPECT_EQ(r.combinations, 8u + 28u + 56u);
    for (const auto& m : r.methods) EXPECT_EQ(m.fusions, m.name == "channel-sum" ? 56u : 84u) << m.name;
    EXPECT_GE(r.fusions, 56u + 6u * 84u);  // the greedy search's longer sequences come on top
}

TEST_F(Study, BadDatasetsAndOptionsGetOneLine) {
    const Dataset d = read_dataset(dir_);
    StudyOptions unknown = small_options(2);
    unknown.objects = {"ridge", "teapot"};
    expect_error([&] { run_study(d, unknown, nullptr); }, dir_, ErrorKind::InvalidArgument, "no object \"teapot\"");
    expect_error([&] { run_study(d, small_options(0), nullptr); }, "study", ErrorKind::InvalidArgument, "max_k");
    StudyOptions sensor = small_options(2);
    sensor.serial = "NOPE";
    expect_error([&] { run_study(d, sensor, nullptr); }, dir_, ErrorKind::InvalidArgument, "NOPE");

    const std::string no_static = tmp_.file("no-static");
    StudyDatasetSpec spec;
    spec.with_static = false;
    write_study_dataset(no_static, spec);
    expect_error([&] { run_study(read_dataset(no_static), small_options(2), nullptr); }, no_static,
                 ErrorKind::InvalidArgument, "static setting");

    // 64 settings in combinations of up to 5 would take days: refused before
    // anything is fused; 125 settings are refused outright.
    const std::string many = tmp_.file("many");
    spec = {};
    spec.objects = {"ridge"};
    spec.levels = {0, 5, 10, 15};
    spec.backgrounds_per_setting = 1;
    write_study_dataset(many, spec);
    expect_error([&] { run_study(read_dataset(many), small_options(5), nullptr); }, many, ErrorKind::InvalidArgument,
                 "combinations");
    const std::string too_many = tmp_.file("too-many");
    spec.levels = {0, 5, 10, 12, 15};
    write_study_dataset(too_many, spec);
    expect_error([&] { run_study(read_dataset(too_many), small_options(2), nullptr); }, too_many,
                 ErrorKind::InvalidArgument, "more than 64 settings");
}

}  // namespace
}  // namespace vkfuse::test

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
    EXPECT_EQ(gpu.ranking_method, cpu.ranking_method);
    for (std::size_t i = 0; i < 3; ++i) {
        ASSERT_EQ(gpu.best_pairs[i].size(), cpu.best_pairs[i].size());
        for (std::size_t p = 0; p < cpu.best_pairs[i].size(); ++p)
            EXPECT_EQ(gpu.best_pairs[i][p].settings, cpu.best_pairs[i][p].settings) << "metric " << i << " rank " << p;
        EXPECT_EQ(gpu.best_k[i], cpu.best_k[i]) << "metric " << i;
    }
    EXPECT_EQ(gpu.pairs_in_every_top, cpu.pairs_in_every_top);
    EXPECT_EQ(gpu.best.settings, cpu.best.settings);
    EXPECT_EQ(gpu.best_best_method, cpu.best_best_method);
    EXPECT_EQ(gpu.best_improves_all_objects, cpu.best_improves_all_objects);
    ASSERT_EQ(gpu.static_metrics.size(), 2u);
    for (std::size_t o = 0; o < 2; ++o) {
        EXPECT_NEAR(gpu.static_metrics[o].sharpness, cpu.static_metrics[o].sharpness, 1e-5 * cpu.static_metrics[o].sharpness);
        EXPECT_NEAR(gpu.static_metrics[o].contrast, cpu.static_metrics[o].contrast, 1e-5 * cpu.static_metrics[o].contrast);
    }
}

TEST_F(Study, TheAnalysisMatchesARecount) {
    const Dataset d = read_dataset(dir_);
    const StudyResult r = run_study(d, small_options(2), &ctx());
    const Recount recount{d, study_grid({}), {"ridge", "dots"}};
    ASSERT_EQ(r.settings, recount.grid);
    EXPECT_EQ(r.settings[r.static_setting], Illumination({15, 15, 15}));
    EXPECT_EQ(r.objects, recount.objects);
    // Every method on every pair and object, and every single frame, from
    // scratch with the reference path.
    const std::vector<StudyMethod> methods = study_methods();
    std::vector<std::vector<std::size_t>> pairs;
    for (std::size_t a = 0; a < 8; ++a)
        for (std::size_t b = a + 1; b < 8; ++b) pairs.push_back({a, b});
    // gains[m][p][o]; singles[s][o]
    std::vector<std::vector<std::vector<Gains>>> gains(methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m) {
        if (methods[m].name == "channel-sum") continue;
        for (const auto& p : pairs) {
            std::vector<Gains> per_object;
            for (const std::string& o : recount.objects)
                per_object.push_back(recount.gains(o, {recount.grid[p[0]], recount.grid[p[1]]}, methods[m].spec));
            gains[m].push_back(per_object);
        }
    }
    std::vector<std::vector<Gains>> singles;
    for (std::size_t s = 0; s < 8; ++s) {
        singles.emplace_back();
        for (const std::string& o : recount.objects) singles.back().push_back(recount.gains(o, {recount.grid[s]}, {}));
    }
    const auto mean_of = [](const std::vector<Gains>& g) {
        Gains m;
        for (const Gains& x : g) {
            m.sharpness += x.sharpness / double(g.size());
            m.contrast += x.contrast / double(g.size());
            m.background_diff += x.background_diff / double(g.size());
        }
        return m;
    };
    const auto mean3 = [](const Gains& g) { return (g.sharpness + g.contrast + g.background_diff) / 3; };
    // Improving is strict, counted here with comparisons of the test's own,
    // not with the predicate under test (Gains::improves_all).
    const auto improves = [](const Gains& g) { return g.sharpness > 1 && g.contrast > 1 && g.background_diff > 1; };

    // Per method: the share improving all metrics and the mean gains.
    std::size_t best = methods.size();
    std::vector<double> share(methods.size(), 0);
    std::vector<Gains> means(methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m) {
        ASSERT_EQ(r.methods[m].name, methods[m].name);
        if (gains[m].empty()) {
            EXPECT_EQ(r.methods[m].fusions, 0u) << "channel-sum takes exactly three settings";
            continue;
        }
        std::vector<Gains> all;
        std::size_t improving = 0;
        for (const auto& p : gains[m])
            for (const Gains& g : p) {
                all.push_back(g);
                improving += improves(g) ? 1 : 0;
            }
        share[m] = double(improving) / double(all.size());
        means[m] = mean_of(all);
        EXPECT_EQ(r.methods[m].fusions, 56u);
        EXPECT_NEAR(r.methods[m].improves_all_fraction, share[m], 1.0 / 56 + 1e-12) << methods[m].name;
        expect_close(r.methods[m].mean_gain, means[m], 1e-4, methods[m].name);
        if (best == methods.size() || share[m] > share[best] || (share[m] == share[best] && mean3(means[m]) > mean3(means[best])))
            best = m;
    }
    EXPECT_EQ(r.best_method, methods[best].name);
    EXPECT_EQ(r.ranking_method, r.best_method) << "pairs: channel-sum cannot win";
    // The best pairs of the ranking method, per metric.
    for (std::size_t i = 0; i < 3; ++i) {
        std::vector<std::pair<double, std::vector<std::size_t>>> ranked;
        for (std::size_t p = 0; p < pairs.size(); ++p) ranked.push_back({mean_of(gains[best][p]).of(kAllMetrics[i]), pairs[p]});
        std::stable_sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
        ASSERT_EQ(r.best_pairs[i].size(), 3u);
        for (std::size_t p = 0; p < 3; ++p) {
            EXPECT_EQ(r.best_pairs[i][p].settings, ranked[p].second) << "metric " << i << " rank " << p;
            EXPECT_NEAR(r.best_pairs[i][p].gain.of(kAllMetrics[i]), ranked[p].first, 1e-4 * ranked[p].first);
        }
    }
    // Per metric and object, the size of the best combination of any method.
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t o = 0; o < 2; ++o) {
            double top = -1;
            std::size_t k = 0;
            for (std::size_t s = 0; s < 8; ++s)
                if (singles[s][o].of(kAllMetrics[i]) > top) top = singles[s][o].of(kAllMetrics[i]), k = 1;
            for (std::size_t m = 0; m < methods.size(); ++m)
                for (const auto& p : gains[m])
                    if (p[o].of(kAllMetrics[i]) > top) top = p[o].of(kAllMetrics[i]), k = 2;
            EXPECT_EQ(r.best_k[i][o], k) << "metric " << i << " object " << o;
        }
    // The greedy search: the best single frame, then the best second setting.
    for (std::size_t i = 0; i < 3; ++i) {
        std::size_t first = 0;
        for (std::size_t s = 1; s < 8; ++s)
            if (mean_of(singles[s]).of(kAllMetrics[i]) > mean_of(singles[first]).of(kAllMetrics[i])) first = s;
        ASSERT_EQ(r.greedy[i].size(), 3u);
        EXPECT_EQ(r.greedy[i][0].sequence, std::vector<std::size_t>{first}) << "metric " << i;
        EXPECT_NEAR(r.greedy[i][0].value, mean_of(singles[first]).of(kAllMetrics[i]), 1e-5);
        double top = -1;
        std::size_t second = 0;
        for (std::size_t p = 0; p < pairs.size(); ++p) {
            if (pairs[p][0] != first && pairs[p][1] != first) continue;
            const double v = mean_of(gains[best][p]).of(kAllMetrics[i]);
            if (v > top) top = v, second = pairs[p][0] == first ? pairs[p][1] : pairs[p][0];
        }
        EXPECT_EQ(r.greedy[i][1].sequence, (std::vector<std::size_t>{first, second})) << "metric " << i;
        EXPECT_NEAR(r.greedy[i][1].value, top, 1e-4 * top);
        EXPECT_EQ(r.greedy[i][2].sequence.size(), 3u);
        EXPECT_TRUE(std::equal(r.greedy[i][1].sequence.begin(), r.greedy[i][1].sequence.end(), r.greedy[i][2].sequence.begin()));
    }
    // The pairing: the static setting with each other one.
    ASSERT_EQ(r.pairing.size(), 7u);
    for (const auto& pairing : r.pairing) {
        const std::size_t s = pairing.settings[0];
        const std::vector<std::size_t> pair = {std::min(s, r.static_setting), std::max(s, r.static_setting)};
        const std::size_t p = std::size_t(std::find(pairs.begin(), pairs.end(), pair) - pairs.begin());
        expect_close(pairing.gain, mean_of(gains[best][p]), 1e-4, "pairing with " + r.settings[s].to_string());
    }
    // Best overall: the highest mean gain among the (pair, method) improving
    // everything on every object, else among all.
    for (const bool everywhere : {true, false}) {
        double top = -1;
        std::vector<std::size_t> settings;
        std::string method;
        for (std::size_t m = 0; m < methods.size(); ++m)
            for (std::size_t p = 0; p < gains[m].size(); ++p) {
                if (everywhere && !(improves(gains[m][p][0]) && improves(gains[m][p][1]))) continue;
                if (mean3(mean_of(gains[m][p])) > top) top = mean3(mean_of(gains[m][p])), settings = pairs[p], method = methods[m].name;
            }
        if (top < 0) continue;
        EXPECT_EQ(r.best_improves_all_objects, everywhere);
        EXPECT_EQ(r.best.settings, settings);
        EXPECT_EQ(r.best_best_method, method);
        break;
    }
}

// A fusion that leaves a metric exactly as the static frame had it has not
// improved it: every metric must rise, however little.
TEST(StudyGains, AGainOfExactlyOneIsNoImprovement) {
    const double above = std::nextafter(1.0, 2.0);
    EXPECT_FALSE((Gains{1, 2, 2}).improves_all());
    EXPECT_FALSE((Gains{2, 1, 2}).improves_all());
    EXPECT_FALSE((Gains{2, 2, 1}).improves_all());
    EXPECT_FALSE((Gains{1, 1, 1}).improves_all());
    EXPECT_TRUE((Gains{above, above, above}).improves_all());
    EXPECT_FALSE((Gains{std::nan(""), 2, 2}).improves_all());
}

TEST(StudyOrder, ChannelSumTakesEachChannelFromTheFrameLitMostByItsLed) {
    const std::vector<Illumination> settings = {Illumination({0, 0, 15}), Illumination({0, 15, 0}),
                                                Illumination({15, 0, 0}), Illumination({15, 15, 15})};
    const StudyMethod& channel_sum = method_named("channel-sum");
    EXPECT_EQ(fusion_order(channel_sum, settings, {0, 1, 2}), (std::vector<std::size_t>{2, 1, 0}));
    EXPECT_EQ(fusion_order(channel_sum, settings, {3, 0, 2}), (std::vector<std::size_t>{2, 3, 0}));
    EXPECT_EQ(fusion_order(method_named("wavelet-bior4.4"), settings, {2, 0, 1}), (std::vector<std::size_t>{0, 1, 2}));
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

// A selection of methods scores exactly what the whole study scores for
// them: each method's figures depend on no other method.
TEST_F(Study, ASelectionOfMethodsScoresWhatTheWholeStudyDoesForThem) {
    const Dataset d = read_dataset(dir_);
    StudyOptions o = small_options(3);
    o.objects = {"dots"};
    const StudyResult all = run_study(d, o, &ctx());
    o.methods = {"laplacian", "wavelet-bior4.4", "channel-sum"};
    const StudyResult some = run_study(d, o, &ctx());
    ASSERT_EQ(some.methods.size(), 3u);
    const std::vector<std::string> order = {"channel-sum", "laplacian", "wavelet-bior4.4"};  // the table's
    for (std::size_t i = 0; i < order.size(); ++i) {
        const auto& m = some.methods[i];
        EXPECT_EQ(m.name, order[i]);
        const auto same = std::find_if(all.methods.begin(), all.methods.end(), [&](const auto& x) { return x.name == m.name; });
        ASSERT_NE(same, all.methods.end());
        EXPECT_EQ(m.fusions, same->fusions) << m.name;
        EXPECT_EQ(m.improves_all_fraction, same->improves_all_fraction) << m.name;
        EXPECT_EQ(m.mean_gain.sharpness, same->mean_gain.sharpness) << m.name;
        EXPECT_EQ(m.mean_gain.contrast, same->mean_gain.contrast) << m.name;
        EXPECT_EQ(m.mean_gain.background_diff, same->mean_gain.background_diff) << m.name;
    }
    EXPECT_TRUE(std::any_of(some.methods.begin(), some.methods.end(),
                            [&](const auto& m) { return m.name == some.best_method; }));
    EXPECT_EQ(some.static_metrics.size(), all.static_metrics.size());
}

TEST(StudyMethods, NamesSelectMethodsOrFamiliesInTableOrder) {
    const auto names = [](const std::vector<StudyMethod>& methods) {
        std::vector<std::string> out;
        for (const StudyMethod& m : methods) out.push_back(m.name);
        return out;
    };
    EXPECT_EQ(names(select_study_methods({})), names(study_methods()));
    EXPECT_EQ(names(select_study_methods({"wavelet", "brovey"})),
              (std::vector<std::string>{"brovey", "wavelet-haar", "wavelet-db2", "wavelet-bior2.2", "wavelet-bior4.4"}));
    EXPECT_EQ(names(select_study_methods({"wavelet-db2", "wavelet-db2", "channel-sum"})),
              (std::vector<std::string>{"channel-sum", "wavelet-db2"}));
    expect_error([] { select_study_methods({"brovey", "dwt"}); }, "study methods", ErrorKind::InvalidArgument,
                 "\"dwt\" is none of");
    expect_error([] { select_study_methods({"wavelet-sym4"}, "--methods"); }, "--methods", ErrorKind::InvalidArgument,
                 "wavelet-bior4.4");
    expect_error([] { select_study_methods({"channel-sum"}); }, "study methods", ErrorKind::InvalidArgument,
                 "takes any number");
}

TEST_F(Study, BadDatasetsAndOptionsGetOneLine) {
    const Dataset d = read_dataset(dir_);
    StudyOptions unknown = small_options(2);
    unknown.objects = {"ridge", "teapot"};
    expect_error([&] { run_study(d, unknown, nullptr); }, dir_, ErrorKind::InvalidArgument, "no object \"teapot\"");
    expect_error([&] { run_study(d, small_options(1), nullptr); }, "study", ErrorKind::InvalidArgument, "at least 2");
    StudyOptions twice = small_options(2);
    twice.objects = {"ridge", "dots", "ridge"};
    expect_error([&] { run_study(d, twice, nullptr); }, dir_, ErrorKind::InvalidArgument, "named twice");
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

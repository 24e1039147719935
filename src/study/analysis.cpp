// The paper's analysis of a study's scores (vkfuse/study/study.hpp).
#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/method_table.hpp"
#include "study/table.hpp"

namespace vkfuse::study {
namespace {

double mean_of_three(const Gains& g) { return (g.sharpness + g.contrast + g.background_diff) / 3; }

// Indices of the `top` pairs by `gain_of` (highest first; ties keep the
// table's order, so the result never depends on the sort).
template <class GainOf>
std::vector<std::size_t> top_pairs(const Table& t, std::size_t method, std::size_t top, GainOf gain_of) {
    std::vector<std::size_t> pairs;
    for (std::size_t c = 0; c < t.combinations.size(); ++c)
        if (t.combinations[c].size() == 2 && t.at(c, method)) pairs.push_back(c);
    std::stable_sort(pairs.begin(), pairs.end(),
                     [&](std::size_t a, std::size_t b) { return gain_of(a) > gain_of(b); });
    if (pairs.size() > top) pairs.resize(top);
    return pairs;
}

void summarise_methods(const Table& t, StudyResult& r) {
    for (std::size_t m = 0; m < t.methods; ++m) {
        StudyResult::MethodSummary& s = r.methods[m];
        std::size_t n = 0, improving = 0;
        Gains sum;
        for (std::size_t c = 0; c < t.combinations.size(); ++c) {
            const Gains* g = t.at(c, m);
            if (!g) continue;
            ++s.fusions;
            for (std::size_t o = 0; o < t.objects; ++o, ++n) {
                improving += g[o].improves_all() ? 1 : 0;
                sum.sharpness += g[o].sharpness;
                sum.contrast += g[o].contrast;
                sum.background_diff += g[o].background_diff;
            }
        }
        s.fusions *= t.objects;
        if (n == 0) continue;
        s.improves_all_fraction = double(improving) / double(n);
        s.mean_gain = {sum.sharpness / double(n), sum.contrast / double(n), sum.background_diff / double(n)};
    }
}

std::vector<std::size_t> intersect(std::vector<std::size_t> a, std::vector<std::size_t> b) {
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    std::vector<std::size_t> out;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
    return out;
}

void rank_pairs(const Table& t, std::size_t method, std::size_t top, StudyResult& r) {
    std::vector<std::size_t> everywhere;
    for (std::size_t o = 0; o < t.objects; ++o) {
        std::vector<std::size_t> common;
        for (std::size_t i = 0; i < 3; ++i) {
            const Metric metric = kAllMetrics[i];
            auto pairs = top_pairs(t, method, top, [&](std::size_t c) { return t.at(c, method)[o].of(metric); });
            common = i == 0 ? pairs : intersect(common, pairs);
        }
        everywhere = o == 0 ? common : intersect(everywhere, common);
        std::vector<std::vector<std::size_t>> settings;
        for (std::size_t c : common) settings.push_back(t.combinations[c]);
        r.pairs_in_every_top_per_object.push_back(std::move(settings));
    }
    for (std::size_t c : everywhere) r.pairs_in_every_top.push_back(t.combinations[c]);
    for (std::size_t i = 0; i < 3; ++i) {
        const Metric metric = kAllMetrics[i];
        for (std::size_t c :
             top_pairs(t, method, top, [&](std::size_t c) { return mean_gain(t.at(c, method), t.objects).of(metric); }))
            r.best_pairs[i].push_back({t.combinations[c], mean_gain(t.at(c, method), t.objects)});
    }
}

// Per metric and object, the size of the best-scoring combination of any
// method, single frames included.
void find_best_k(const Table& t, StudyResult& r) {
    for (std::size_t i = 0; i < 3; ++i) {
        const Metric metric = kAllMetrics[i];
        for (std::size_t o = 0; o < t.objects; ++o) {
            double best = -1;
            std::size_t k = 1;
            for (std::size_t s = 0; s < t.singles.size(); ++s)
                if (t.singles[s][o].of(metric) > best) best = t.singles[s][o].of(metric);
            for (std::size_t c = 0; c < t.combinations.size(); ++c)
                for (std::size_t m = 0; m < t.methods; ++m)
                    if (const Gains* g = t.at(c, m); g && g[o].of(metric) > best) {
                        best = g[o].of(metric);
                        k = t.combinations[c].size();
                    }
            r.best_k[i].push_back(k);
        }
    }
}

void find_best(const Table& t, StudyResult& r) {
    for (const bool everywhere : {true, false}) {
        double best = -1;
        for (std::size_t c = 0; c < t.combinations.size(); ++c)
            for (std::size_t m = 0; m < t.methods; ++m) {
                const Gains* g = t.at(c, m);
                if (!g) continue;
                if (everywhere && !std::all_of(g, g + t.objects, [](const Gains& x) { return x.improves_all(); }))
                    continue;
                const Gains mean = mean_gain(g, t.objects);
                if (mean_of_three(mean) > best) {
                    best = mean_of_three(mean);
                    r.best = {t.combinations[c], mean};
                    r.best_best_method = r.methods[m].name;
                    r.best_improves_all_objects = everywhere;
                }
            }
        if (best >= 0) return;
    }
}

}  // namespace

bool takes_any_count(const StudyMethod& m) { return core::method_info(m.spec.method).exact_frames == 0; }

Gains mean_gain(const Gains* g, std::size_t objects) {
    Gains sum;
    for (std::size_t o = 0; o < objects; ++o) {
        sum.sharpness += g[o].sharpness;
        sum.contrast += g[o].contrast;
        sum.background_diff += g[o].background_diff;
    }
    const double n = double(objects);
    return {sum.sharpness / n, sum.contrast / n, sum.background_diff / n};
}

std::size_t analyse(const Table& t, const std::vector<StudyMethod>& methods, int top, StudyResult& r) {
    summarise_methods(t, r);
    // Only methods that fused something compete (channel-sum needs
    // combinations of exactly three). The share improving every metric
    // decides; where it ties (none improving anything, often) the mean of
    // the three mean gains does.
    const auto better = [&](std::size_t a, std::size_t b) {
        const auto &x = r.methods[a], &y = r.methods[b];
        if (x.improves_all_fraction != y.improves_all_fraction) return x.improves_all_fraction > y.improves_all_fraction;
        return mean_of_three(x.mean_gain) > mean_of_three(y.mean_gain);
    };
    std::size_t best = t.methods, ranking = t.methods;
    for (std::size_t m = 0; m < t.methods; ++m) {
        if (r.methods[m].fusions == 0) continue;
        if (best == t.methods || better(m, best)) best = m;
        if (takes_any_count(methods[m]) && (ranking == t.methods || better(m, ranking))) ranking = m;
    }
    if (best == t.methods) {  // combinations of one setting only: nothing was fused
        best = ranking = std::size_t(std::find_if(methods.begin(), methods.end(), takes_any_count) - methods.begin());
    }
    r.best_method = r.methods[best].name;
    if (takes_any_count(methods[best])) ranking = best;
    rank_pairs(t, ranking, std::size_t(top), r);
    find_best_k(t, r);
    find_best(t, r);
    return ranking;
}

}  // namespace vkfuse::study

namespace vkfuse {

double Gains::of(Metric metric) const {
    switch (metric) {
        case Metric::Sharpness: return sharpness;
        case Metric::Contrast: return contrast;
        case Metric::BackgroundDiff: return background_diff;
    }
    return 0;
}

}  // namespace vkfuse

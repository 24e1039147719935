// run_study (vkfuse/study/study.hpp): scores every combination with every
// method, then the greedy search and the pairing, which may need more.
#include "vkfuse/study/study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>

#include "core/method_table.hpp"
#include "study/evaluator.hpp"
#include "study/study_data.hpp"
#include "study/table.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {
namespace study {
namespace {

// Combinations a study scores at most (per method): 22 times the paper's
// grid (23 settings, up to 5), about 200 MiB of scores and days of work.
constexpr std::size_t kMaxCombinations = 1'000'000;

bool takes(const StudyMethod& m, std::size_t k) {
    const int exact = core::method_info(m.spec.method).exact_frames;
    return k >= 2 && (exact == 0 || std::size_t(exact) == k);
}

// n choose k, saturating at kMaxCombinations + 1.
std::size_t choose(std::size_t n, std::size_t k) {
    double c = 1;
    for (std::size_t i = 0; i < k; ++i) c = c * double(n - i) / double(i + 1);
    return c > double(kMaxCombinations) ? kMaxCombinations + 1 : std::size_t(std::llround(c));
}

// Every k-subset of 0..n-1, ascending, in lexicographic order.
void append_subsets(std::size_t n, std::size_t k, std::vector<std::vector<std::size_t>>& out) {
    if (k > n) return;
    std::vector<std::size_t> c(k);
    for (std::size_t i = 0; i < k; ++i) c[i] = i;
    while (true) {
        out.push_back(c);
        std::size_t i = k;
        while (i > 0 && c[i - 1] == n - k + (i - 1)) --i;
        if (i == 0) return;
        ++c[i - 1];
        for (std::size_t j = i; j < k; ++j) c[j] = c[j - 1] + 1;
    }
}

void check_options(const StudyOptions& o) {
    if (o.max_k < 2)
        throw Error(ErrorKind::InvalidArgument, "study: max_k must be at least 2 (one setting alone is no fusion)");
    if (o.greedy_max < 1) throw Error(ErrorKind::InvalidArgument, "study: greedy_max must be at least 1");
    if (o.top < 1) throw Error(ErrorKind::InvalidArgument, "study: top must be at least 1");
}

std::vector<Gains> gains_of(const std::vector<Metrics>& metrics, const std::vector<Metrics>& reference) {
    std::vector<Gains> g;
    for (std::size_t o = 0; o < metrics.size(); ++o)
        g.push_back({metrics[o].sharpness / reference[o].sharpness, metrics[o].contrast / reference[o].contrast,
                     *metrics[o].background_diff / *reference[o].background_diff});
    return g;
}

// check_study_shape once the options are checked and the methods selected.
void check_shape(const StudyShape& shape, const StudyOptions& options, const std::vector<StudyMethod>& methods,
                 const std::string& subject) {
    check_study_size(shape.settings, shape.objects, shape.height, shape.width, subject);
    const std::size_t n = shape.settings;
    const std::size_t most = std::min<std::size_t>(std::size_t(options.max_k), n);
    for (const StudyMethod& m : methods)
        for (std::size_t k = 2; k <= most; ++k)
            if (takes(m, k)) try {
                    validate(m.spec, shape.height, shape.width, 3, int(k));
                } catch (const Error& e) {
                    throw Error(ErrorKind::InvalidArgument, subject + ": " + std::to_string(shape.width) + "x" +
                                                                std::to_string(shape.height) +
                                                                " frames do not suit " + m.name + " (" + e.what() + ")");
                }
    std::size_t count = 0;
    for (std::size_t k = 2; k <= most; ++k) count += choose(n, k);
    if (count > kMaxCombinations)
        throw Error(ErrorKind::InvalidArgument, subject + ": " + std::to_string(n) +
                                                    " settings in combinations of up to " +
                                                    std::to_string(options.max_k) + " make more than " +
                                                    std::to_string(kMaxCombinations) + " combinations; take fewer (max_k)");
}

class Study {
public:
    Study(const Dataset& dataset, const StudyOptions& options, Context* context)
        : options_(checked(options)), methods_(select_study_methods(options.methods)),
          data_(load_study_data(dataset, options.serial, options.objects)), evaluator_(data_, context) {
        check_shape({data_.settings.size(), data_.objects, data_.height, data_.width}, options, methods_,
                    dataset.directory);
        const std::size_t n = data_.settings.size();
        for (std::size_t k = 2; k <= std::min<std::size_t>(std::size_t(options.max_k), n); ++k)
            append_subsets(n, k, table_.combinations);
        for (std::size_t c = 0; c < table_.combinations.size(); ++c) index_[table_.combinations[c]] = c;
        table_.methods = methods_.size();
        table_.objects = data_.objects.size();
        planned_ = n;  // the single frames, scored once
        for (const auto& c : table_.combinations)
            for (const StudyMethod& m : methods_) planned_ += takes(m, c.size()) ? 1 : 0;
    }

    StudyResult run(std::string backend) {
        const auto start = std::chrono::steady_clock::now();
        StudyResult r;
        r.backend = std::move(backend);
        r.settings = data_.settings;
        r.objects = data_.objects;
        r.static_setting = data_.static_setting;
        score_singles(r);
        score_table();
        for (const StudyMethod& m : methods_) r.methods.push_back({m.name, 0, {}, 0});
        ranking_ = analyse(table_, methods_, options_.top, r);
        r.ranking_method = methods_[ranking_].name;
        for (const StudyMethod& m : methods_)
            if (m.name == r.best_best_method) r.best.settings = fusion_order(m, data_.settings, r.best.settings);
        greedy(r);
        pair_with_static(r);
        r.combinations = table_.combinations.size() + data_.settings.size();
        r.fusions = fusions_;
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return r;
    }

private:
    // The options are checked before any frame is read.
    static const StudyOptions& checked(const StudyOptions& o) {
        check_options(o);
        return o;
    }

    void progress() {
        if (options_.progress) options_.progress(done_, planned_);
    }

    void score_singles(StudyResult& r) {
        std::vector<std::vector<Metrics>> metrics;
        for (std::size_t s = 0; s < data_.settings.size(); ++s) {
            const std::size_t one[] = {s};
            metrics.push_back(evaluator_.score(methods_.front(), one));
            ++done_;
            progress();
        }
        reference_ = metrics[data_.static_setting];
        for (std::size_t o = 0; o < data_.objects.size(); ++o) {
            const Metrics& m = reference_[o];
            if (!(m.sharpness > 0 && m.contrast > 0 && *m.background_diff > 0))
                throw Error(ErrorKind::InvalidArgument,
                            "object \"" + data_.objects[o] + "\": its frame under the static setting " +
                                data_.settings[data_.static_setting].to_string() +
                                " has a zero metric, which no gain can be measured against");
        }
        r.static_metrics = reference_;
        for (const auto& m : metrics) table_.singles.push_back(gains_of(m, reference_));
    }

    // Method by method, the combinations of each size in batches: a batch is
    // what one call to the evaluator fuses, and one step of progress each.
    void score_table() {
        const std::size_t M = methods_.size(), O = data_.objects.size(), C = table_.combinations.size();
        table_.gains.assign(C * M * O, Gains{});
        table_.scored.assign(C * M, false);
        constexpr std::size_t kPerStep = 100;  // combinations per step, about
        for (std::size_t m = 0; m < M; ++m)
            for (std::size_t first = 0; first < C;) {
                const std::size_t k = table_.combinations[first].size();
                const bool scored = takes(methods_[m], k);
                const std::size_t batch = scored ? evaluator_.batch(methods_[m], k) : 1;
                const std::size_t step = std::max<std::size_t>(1, kPerStep / batch) * batch;
                std::size_t end = first;
                while (end < C && end - first < step && table_.combinations[end].size() == k) ++end;
                if (scored) {
                    std::vector<std::vector<std::size_t>> orders;
                    for (std::size_t c = first; c < end; ++c)
                        orders.push_back(fusion_order(methods_[m], data_.settings, table_.combinations[c]));
                    const auto scores = evaluator_.score_many(methods_[m], orders);
                    for (std::size_t c = first; c < end; ++c) {
                        const std::vector<Gains> g = gains_of(scores[c - first], reference_);
                        std::copy(g.begin(), g.end(), table_.gains.begin() + std::ptrdiff_t((c * M + m) * O));
                        table_.scored[c * M + m] = true;
                        fusions_ += O;
                        ++done_;
                    }
                    progress();
                }
                first = end;
            }
    }

    // The ranking method's mean gains for a set of settings (ascending): from
    // the table or scored before, else nullopt.
    std::optional<Gains> known(const std::vector<std::size_t>& settings) const {
        if (settings.size() == 1) return mean_gain(table_.singles[settings[0]].data(), table_.objects);
        if (auto it = index_.find(settings); it != index_.end())
            if (const Gains* g = table_.at(it->second, ranking_)) return mean_gain(g, table_.objects);
        if (auto it = extra_.find(settings); it != extra_.end()) return it->second;
        return std::nullopt;
    }
    // The same for several sets, those not known scored now in one batch and
    // kept. Each set counts as one step of progress either way, so that the
    // plan made up front holds.
    std::vector<Gains> means_for(const std::vector<std::vector<std::size_t>>& sets) {
        std::vector<std::vector<std::size_t>> unknown;
        for (const auto& s : sets)
            if (!known(s)) unknown.push_back(s);
        if (!unknown.empty()) {
            const auto scores = evaluator_.score_many(methods_[ranking_], unknown);
            for (std::size_t i = 0; i < unknown.size(); ++i) {
                extra_[unknown[i]] = mean_gain(gains_of(scores[i], reference_).data(), table_.objects);
                fusions_ += table_.objects;
            }
        }
        std::vector<Gains> out;
        for (const auto& s : sets) out.push_back(*known(s));
        return out;
    }

    void greedy(StudyResult& r) {
        const std::size_t n = data_.settings.size(), longest = std::min<std::size_t>(std::size_t(options_.greedy_max), n);
        for (std::size_t length = 2; length <= longest; ++length) planned_ += 3 * (n - length + 1);
        planned_ += n - 1;  // the pairing with the static setting, after
        for (std::size_t i = 0; i < 3; ++i) {
            const Metric metric = kAllMetrics[i];
            std::vector<std::size_t> sequence;
            for (std::size_t length = 1; length <= longest; ++length) {
                std::vector<std::size_t> candidates;
                std::vector<std::vector<std::size_t>> sets;
                for (std::size_t s = 0; s < n; ++s) {
                    if (std::find(sequence.begin(), sequence.end(), s) != sequence.end()) continue;
                    std::vector<std::size_t> set = sequence;
                    set.push_back(s);
                    std::sort(set.begin(), set.end());
                    candidates.push_back(s);
                    sets.push_back(std::move(set));
                }
                const std::vector<Gains> means = means_for(sets);
                std::size_t pick = n;
                double value = -1;
                for (std::size_t c = 0; c < candidates.size(); ++c) {
                    const double v = means[c].of(metric);
                    if (v > value) {
                        value = v;
                        pick = candidates[c];
                    }
                }
                if (length > 1) {
                    done_ += candidates.size();
                    progress();
                }
                sequence.push_back(pick);
                r.greedy[i].push_back({length, sequence, value});
            }
        }
    }

    void pair_with_static(StudyResult& r) {
        const std::size_t s0 = data_.static_setting;
        std::vector<std::vector<std::size_t>> pairs;
        for (std::size_t s = 0; s < data_.settings.size(); ++s)
            if (s != s0) pairs.push_back({std::min(s, s0), std::max(s, s0)});
        const std::vector<Gains> means = means_for(pairs);
        for (std::size_t p = 0, s = 0; s < data_.settings.size(); ++s)
            if (s != s0) r.pairing.push_back({{s}, means[p++]});
        done_ += pairs.size();
        progress();
    }

    const StudyOptions& options_;
    std::vector<StudyMethod> methods_;  // before the data: a bad name fails before any frame is read
    StudyData data_;
    Evaluator evaluator_;
    Table table_;
    std::map<std::vector<std::size_t>, std::size_t> index_;
    std::map<std::vector<std::size_t>, Gains> extra_;  // ranking method, beyond the table
    std::vector<Metrics> reference_;                    // per object: the static frame's
    std::size_t ranking_ = 0;
    std::size_t done_ = 0, planned_ = 0, fusions_ = 0;
};

}  // namespace
}  // namespace study

std::vector<StudyMethod> study_methods() {
    std::vector<StudyMethod> out;
    for (const core::MethodInfo& info : core::method_table()) {
        FusionSpec spec;
        spec.method = info.method;
        if (!info.uses_wavelet) {
            out.push_back({std::string(info.name), spec});
            continue;
        }
        for (Wavelet w : {Wavelet::Haar, Wavelet::Db2, Wavelet::Bior22, Wavelet::Bior44}) {
            spec.wavelet = w;
            out.push_back({std::string(info.name) + "-" + std::string(to_string(w)), spec});
        }
    }
    return out;
}

std::vector<StudyMethod> select_study_methods(const std::vector<std::string>& names, const std::string& what) {
    const std::vector<StudyMethod> all = study_methods();
    if (names.empty()) return all;
    const auto method_of = [](const StudyMethod& m) { return std::string(core::method_info(m.spec.method).name); };
    std::vector<bool> chosen(all.size(), false);
    for (const std::string& name : names) {
        bool known = false;
        for (std::size_t i = 0; i < all.size(); ++i)
            if (all[i].name == name || method_of(all[i]) == name) chosen[i] = known = true;
        if (known) continue;
        std::string choices;  // in table order, a family-wide name before its families
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (i > 0) choices += ", ";
            if (all[i].name != method_of(all[i]) && (i == 0 || method_of(all[i - 1]) != method_of(all[i])))
                choices += method_of(all[i]) + " (every family), ";
            choices += all[i].name;
        }
        throw Error(ErrorKind::InvalidArgument, what + ": \"" + name + "\" is none of " + choices);
    }
    std::vector<StudyMethod> out;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (chosen[i]) out.push_back(all[i]);
    if (std::none_of(out.begin(), out.end(), study::takes_any_count))
        throw Error(ErrorKind::InvalidArgument,
                    what + ": " + out.front().name +
                        " alone fuses a fixed number of settings; the greedy search and the pairing need a method "
                        "that takes any number (add one)");
    return out;
}

std::vector<std::size_t> fusion_order(const StudyMethod& method, const std::vector<Illumination>& settings,
                                      std::vector<std::size_t> combination) {
    std::sort(combination.begin(), combination.end());
    if (!core::method_info(method.spec.method).frames_are_channels) return combination;
    std::vector<std::size_t> best = combination, order = combination;
    const auto score = [&](const std::vector<std::size_t>& o) {
        int sum = 0;
        for (std::size_t channel = 0; channel < o.size() && channel < 3; ++channel)
            sum += settings[o[channel]].level(int(channel));
        return sum;
    };
    while (std::next_permutation(order.begin(), order.end()))
        if (score(order) > score(best)) best = order;
    return best;
}

void check_study_shape(const StudyShape& shape, const StudyOptions& options, const std::string& subject) {
    study::check_options(options);
    study::check_shape(shape, options, select_study_methods(options.methods), subject);
}

StudyResult run_study(const Dataset& dataset, const StudyOptions& options, Context* context) {
    study::Study s(dataset, options, context);
    return s.run(context ? "vulkan (" + context->device().name + ")" : std::string("cpu"));
}

}  // namespace vkfuse

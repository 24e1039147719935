#include "study/study_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/atomic_write.hpp"
#include "io/json_value.hpp"
#include "study/study_plots.hpp"

namespace vkfuse::cli {
namespace {

using json::Value;

Value setting_json(const Illumination& s) {
    Value::Array levels;
    for (int v : s.levels()) levels.emplace_back(v);
    return levels;
}

Value settings_json(const StudyResult& r, const std::vector<std::size_t>& indices) {
    Value::Array out;
    for (std::size_t i : indices) out.push_back(setting_json(r.settings[i]));
    return out;
}

Value gains_json(const Gains& g) {
    return Value::Object{{"sharpness", g.sharpness}, {"contrast", g.contrast}, {"background_diff", g.background_diff}};
}

Value metrics_json(const Metrics& m) {
    return Value::Object{{"sharpness", m.sharpness},
                         {"contrast", m.contrast},
                         {"background_diff", m.background_diff ? Value(*m.background_diff) : Value()}};
}

std::string names(const StudyResult& r, const std::vector<std::size_t>& indices, const char* separator = " + ") {
    std::string out;
    for (std::size_t i : indices) out += (out.empty() ? "" : separator) + ("(" + r.settings[i].to_string() + ")");
    return out;
}

std::size_t peak(const std::vector<StudyResult::Step>& steps) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < steps.size(); ++i)
        if (steps[i].value > steps[best].value) best = i;
    return steps.empty() ? 0 : steps[best].n;
}

std::string results_json(const std::string& dataset, const StudyResult& r, const StudyFindings& f) {
    Value::Array methods;
    for (const auto& m : r.methods)
        methods.push_back(Value::Object{{"name", m.name},
                                        {"improves_all_fraction", m.improves_all_fraction},
                                        {"mean_gain", gains_json(m.mean_gain)},
                                        {"fusions", std::uint64_t(m.fusions)}});
    Value::Array pairing;
    for (const auto& p : r.pairing)
        pairing.push_back(Value::Object{{"setting", setting_json(r.settings[p.settings[0]])},
                                        {"sharpness_gain", p.gain.sharpness},
                                        {"contrast_gain", p.gain.contrast},
                                        {"background_diff_gain", p.gain.background_diff}});
    Value::Object greedy, best_pairs, best_k;
    for (std::size_t i = 0; i < 3; ++i) {
        const std::string metric(to_string(kAllMetrics[i]));
        Value::Array steps;
        for (const auto& s : r.greedy[i])
            steps.push_back(Value::Object{
                {"n", std::uint64_t(s.n)}, {"sequence", settings_json(r, s.sequence)}, {"value", s.value}});
        greedy.emplace_back(metric, std::move(steps));
        Value::Array pairs;
        for (const auto& p : r.best_pairs[i])
            pairs.push_back(Value::Object{{"settings", settings_json(r, p.settings)}, {"gain", gains_json(p.gain)}});
        best_pairs.emplace_back(metric, std::move(pairs));
        Value::Array ks;
        for (std::size_t k : r.best_k[i]) ks.emplace_back(std::uint64_t(k));
        best_k.emplace_back(metric, std::move(ks));
    }
    Value::Array objects, in_every_top_per_object, in_every_top;
    for (std::size_t o = 0; o < r.objects.size(); ++o) {
        objects.push_back(Value::Object{{"name", r.objects[o]}, {"static_metrics", metrics_json(r.static_metrics[o])}});
        Value::Array pairs;
        for (const auto& p : r.pairs_in_every_top_per_object[o]) pairs.push_back(settings_json(r, p));
        in_every_top_per_object.push_back(Value::Object{{"object", r.objects[o]}, {"pairs", std::move(pairs)}});
    }
    for (const auto& p : r.pairs_in_every_top) in_every_top.push_back(settings_json(r, p));
    Value::Array settings;
    for (const auto& s : r.settings) settings.push_back(setting_json(s));
    const Value root = Value::Object{
        {"dataset", dataset},
        {"backend", r.backend},
        {"best_method", r.best_method},
        {"ranking_method", r.ranking_method},
        {"methods", std::move(methods)},
        {"pairing", std::move(pairing)},
        {"greedy", std::move(greedy)},
        {"best",
         Value::Object{{"settings", settings_json(r, r.best.settings)},
                       {"method", r.best_best_method},
                       {"gain", gains_json(r.best.gain)},
                       {"improves_all_on_every_object", r.best_improves_all_objects}}},
        {"best_pairs", std::move(best_pairs)},
        {"pairs_in_every_top", std::move(in_every_top)},
        {"pairs_in_every_top_per_object", std::move(in_every_top_per_object)},
        {"best_k", std::move(best_k)},
        {"settings", std::move(settings)},
        {"static_setting", setting_json(r.settings[r.static_setting])},
        {"objects", std::move(objects)},
        {"findings",
         Value::Object{{"wavelet_most_likely_to_improve_all", f.wavelet_tested ? Value(f.wavelet_most_likely) : Value()},
                       {"pair_15_15_15_0_15_0_among_best", f.has_best_pair ? Value(f.best_pair_among_best) : Value()},
                       {"pair_15_15_15_0_15_0_among_best_by", f.best_pair_metrics},
                       {"sharpness_greedy_peak_n", std::uint64_t(f.sharpness_greedy_n)},
                       {"sharpness_best_k_2_to_4_share", f.sharpness_2_to_4_share},
                       {"contrast_greedy_peak_n", std::uint64_t(f.contrast_greedy_n)},
                       {"contrast_best_single_frame_share", f.contrast_single_share}}},
        {"combinations", std::uint64_t(r.combinations)},
        {"fusions", std::uint64_t(r.fusions)},
        {"seconds", r.seconds},
    };
    return json::write(root) + "\n";
}

std::string verdict(bool holds) { return holds ? "**holds here**" : "**does not hold here**"; }

std::string percent(double share) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f %%", share * 100);
    return text;
}

std::string fixed(double v, int digits = 3) {
    char text[48];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

std::string report_md(const std::string& dataset, const StudyResult& r, const StudyFindings& f) {
    std::string md = "# Illumination study of " + dataset + "\n\n";
    md += std::to_string(r.objects.size()) + " objects, " + std::to_string(r.settings.size()) + " settings, " +
          std::to_string(r.combinations) + " combinations, " + std::to_string(r.fusions) + " fusions scored in " +
          fixed(r.seconds, 1) + " s on " + r.backend + ". Every gain is a metric of the fused image divided by the " +
          "same object's frame under the static setting (" + r.settings[r.static_setting].to_string() +
          "); above 1 is better. A fused image's background is the same fusion of the settings' backgrounds.\n\n";
    if (r.methods.size() < study_methods().size()) {
        md += "Methods studied (a selection):";
        for (const auto& m : r.methods) md += " " + m.name + (&m == &r.methods.back() ? ".\n\n" : ",");
    }
    md += "## The paper's findings, on this sensor\n\n";
    md += "1. *Wavelet fusion is the most likely to improve every metric at once*: " +
          (f.wavelet_tested ? verdict(f.wavelet_most_likely) + ". The most likely here is " + r.best_method +
                                  " (see the table below).\n"
                            : std::string("not tested: the study's methods leave out the wavelet or every other "
                                          "method.\n"));
    md += "2. *(15,15,15) + (0,15,0) is among the best pairs*: ";
    const std::string top = "the top " + std::to_string(r.best_pairs[0].size()) + " pairs of " + r.ranking_method;
    md += !f.has_best_pair ? "not tested: the dataset lacks one of the two settings.\n"
          : f.best_pair_among_best
              ? verdict(true) + ": it is among " + top + " by " + f.best_pair_metrics + " (listed below).\n"
              : verdict(false) + ": it is not among " + top + " by any metric (listed below).\n";
    md += "3. *2-4 frames maximise sharpness*: " +
          std::string(verdict(f.sharpness_greedy_n >= 2 && f.sharpness_greedy_n <= 4)) +
          ". The greedy sharpness gain peaks at n = " + std::to_string(f.sharpness_greedy_n) + "; for " +
          percent(f.sharpness_2_to_4_share) + " of the objects the sharpest combination has 2-4 settings.\n";
    md += "4. *One frame often maximises contrast*: " + std::string(verdict(f.contrast_single_share >= 0.5)) +
          ". For " + percent(f.contrast_single_share) +
          " of the objects no fusion beats the best single frame's contrast; the greedy contrast gain peaks at n = " +
          std::to_string(f.contrast_greedy_n) + ".\n\n";
    md += "Where a finding does not hold, that is this sensor's (or the simulator's) answer: nothing here is tuned "
          "to agree with the paper.\n\n";
    md += "## Methods\n\n| method | improves all metrics | mean sharpness gain | mean contrast gain | mean "
          "background-difference gain | fusions |\n|---|---|---|---|---|---|\n";
    for (const auto& m : r.methods)
        md += "| " + m.name + " | " + percent(m.improves_all_fraction) + " | " + fixed(m.mean_gain.sharpness) + " | " +
              fixed(m.mean_gain.contrast) + " | " + fixed(m.mean_gain.background_diff) + " | " +
              std::to_string(m.fusions) + " |\n";
    md += "\n![methods](methods.svg)\n\n## Best pairs (" + (r.best_pairs[0].empty() ? std::string("none scored") : r.ranking_method) + ")\n\n";
    for (std::size_t i = 0; i < 3; ++i) {
        md += "- " + std::string(to_string(kAllMetrics[i])) + ":";
        for (const auto& p : r.best_pairs[i])
            md += " " + names(r, p.settings) + " " + fixed(p.gain.of(kAllMetrics[i])) + ";";
        md += "\n";
    }
    md += "- among the top of every metric on every object: " +
          (r.pairs_in_every_top.empty() ? std::string("none") : std::string());
    for (const auto& p : r.pairs_in_every_top) md += names(r, p) + "; ";
    md += "\n\n## Greedy sequences (" + r.ranking_method + ")\n\n![greedy](greedy.svg)\n\n";
    for (std::size_t i = 0; i < 3; ++i) {
        md += "- " + std::string(to_string(kAllMetrics[i])) + ": ";
        for (const auto& s : r.greedy[i]) md += "n=" + std::to_string(s.n) + " " + fixed(s.value) + ", ";
        if (!r.greedy[i].empty()) md += "sequence " + names(r, r.greedy[i].back().sequence, ", ");
        md += "\n";
    }
    md += "\n## The static setting paired with each other (" + r.ranking_method + ")\n\n![pairing](pairing.svg)\n\n";
    md += "## Best overall\n\n" + names(r, r.best.settings) + " fused by " + r.best_best_method + ": sharpness x" +
          fixed(r.best.gain.sharpness) + ", contrast x" + fixed(r.best.gain.contrast) + ", background difference x" +
          fixed(r.best.gain.background_diff) +
          (r.best_improves_all_objects ? " (improves every metric on every object).\n"
                                       : " (no combination improves every metric on every object).\n");
    return md;
}

}  // namespace

StudyFindings study_findings(const StudyResult& r) {
    StudyFindings f;
    const auto is_wavelet = [](const std::string& name) { return name.rfind("wavelet", 0) == 0; };
    // Only methods that fused something competed (analyse()): channel-sum
    // chosen beside a wavelet fuses nothing without combinations of three.
    const auto competed = [&](bool wavelet) {
        return std::any_of(r.methods.begin(), r.methods.end(),
                           [&](const auto& m) { return m.fusions > 0 && is_wavelet(m.name) == wavelet; });
    };
    f.wavelet_tested = competed(true) && competed(false);
    f.wavelet_most_likely = is_wavelet(r.best_method);
    const auto find = [&](const Illumination& s) {
        return std::size_t(std::find(r.settings.begin(), r.settings.end(), s) - r.settings.begin());
    };
    const std::size_t a = find(Illumination({15, 15, 15})), b = find(Illumination({0, 15, 0}));
    f.has_best_pair = a < r.settings.size() && b < r.settings.size();
    const std::vector<std::size_t> pair = {std::min(a, b), std::max(a, b)};
    for (std::size_t i = 0; i < 3; ++i)
        for (const auto& p : r.best_pairs[i])
            if (f.has_best_pair && p.settings == pair) {
                f.best_pair_among_best = true;
                f.best_pair_metrics += (f.best_pair_metrics.empty() ? "" : ", ") + std::string(to_string(kAllMetrics[i]));
            }
    f.sharpness_greedy_n = peak(r.greedy[0]);
    f.contrast_greedy_n = peak(r.greedy[1]);
    const auto share = [&](const std::vector<std::size_t>& ks, auto predicate) {
        return ks.empty() ? 0.0 : double(std::count_if(ks.begin(), ks.end(), predicate)) / double(ks.size());
    };
    f.sharpness_2_to_4_share = share(r.best_k[0], [](std::size_t k) { return k >= 2 && k <= 4; });
    f.contrast_single_share = share(r.best_k[1], [](std::size_t k) { return k == 1; });
    return f;
}

void write_study(const std::string& directory, const std::string& dataset, const StudyResult& r) {
    const StudyFindings f = study_findings(r);
    const auto write_text = [&](const std::string& name, const std::string& text) {
        const std::string path = directory + "/" + name;
        io::write_atomically(path, [&](std::FILE* out) { io::write_all(out, text, path); });
    };
    write_text("results.json", results_json(dataset, r, f));
    write_text("report.md", report_md(dataset, r, f));
    write_text("methods.svg", methods_svg(r));
    write_text("greedy.svg", greedy_svg(r));
    write_text("pairing.svg", pairing_svg(r));
}

}  // namespace vkfuse::cli

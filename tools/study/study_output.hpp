// study_output.hpp - what `vkfuse study --out DIR` writes:
//   DIR/results.json   every figure of the study (vkfuse/study/study.hpp)
//   DIR/report.md      the findings a person reads, the paper's beside ours
//   DIR/methods.svg    per method, the share of fusions improving every metric
//   DIR/greedy.svg     per metric, the greedy sequence's gain against n
//   DIR/pairing.svg    the static setting fused with each other one: gains
// DIR is a StagedDirectory's staging directory. No name comes from the
// dataset: objects and settings appear only inside the files.
#pragma once
#include <string>

#include "vkfuse/study/study.hpp"

namespace vkfuse::cli {

// The paper's findings, checked on a study's result.
struct StudyFindings {
    // best_method is a wavelet; tested only where a wavelet and another
    // method both fused something (--methods may leave either out, and
    // channel-sum fuses only combinations of three).
    bool wavelet_tested = false;
    bool wavelet_most_likely = false;
    // (15,15,15)+(0,15,0) among the best pairs of some metric; nullopt-like
    // state when the dataset lacks either setting (has_best_pair false).
    bool has_best_pair = false;
    bool best_pair_among_best = false;
    std::string best_pair_metrics;           // the metrics whose best pairs hold it: "sharpness, contrast"
    std::size_t sharpness_greedy_n = 0;      // n where the greedy sharpness gain peaks
    double sharpness_2_to_4_share = 0;       // objects whose sharpest combination has 2-4 settings
    std::size_t contrast_greedy_n = 0;
    double contrast_single_share = 0;        // objects whose best contrast is a single frame
};
StudyFindings study_findings(const StudyResult& result);

// Writes the files above into directory; throws Error(Io) naming a file.
void write_study(const std::string& directory, const std::string& dataset, const StudyResult& result);

}  // namespace vkfuse::cli

// vkfuse/study/study.hpp - the paper's search, on a sensor's own dataset:
// which LED settings, fused by which method, improve the sensor's images.
//
// A dataset holding, per object, a frame under each LED setting and a
// background (nothing pressed) under each is scored for every combination of
// 1..max_k settings and every fusion method (or those options.methods names):
// the sharpness, RMS contrast and difference with background of each fused
// image, relative to the same object's frame under the static setting (every
// LED at full level). The background a fused image is compared with is the
// same fusion of the settings' backgrounds, as `vkfuse run` does. Then the
// paper's analysis: which method most often improves every metric at once,
// the best pairs, the greedy best sequence per metric, and the pairing of
// the static setting with each other one.
#pragma once
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse {

// One fusion method of the study: a method with its default levels and rules,
// and for the wavelet one family.
struct StudyMethod {
    std::string name;  // "wavelet-bior4.4", "laplacian", "brovey", "channel-sum"
    FusionSpec spec;
};
// Every method, the wavelet once per family, in the method table's order.
std::vector<StudyMethod> study_methods();
// The methods a study of `names` scores, in study_methods() order: each name
// is a study method's ("wavelet-bior4.4") or a method's ("wavelet": every
// family); none: every method. Throws Error(InvalidArgument), its message
// starting with `what`, for a name that is neither, and for a selection
// without a method that takes any number of settings (channel-sum alone
// fuses exactly three, and the greedy search and the pairing need more).
std::vector<StudyMethod> select_study_methods(const std::vector<std::string>& names,
                                              const std::string& what = "study methods");

// The order `method` fuses a combination in (indices into settings, given in
// any order): ascending, except for channel-sum, which takes R, G and B from
// the frames lit most by the red, green and blue LED (the permutation with
// the highest sum of each frame's level of its channel; the earliest in
// ascending order on ties).
std::vector<std::size_t> fusion_order(const StudyMethod& method, const std::vector<Illumination>& settings,
                                      std::vector<std::size_t> combination);

// A fused image's metrics divided by those of the same object's static frame:
// above 1 is an improvement.
struct Gains {
    double sharpness = 0;
    double contrast = 0;
    double background_diff = 0;

    double of(Metric metric) const;
    bool improves_all() const { return sharpness > 1 && contrast > 1 && background_diff > 1; }
};

struct StudyOptions {
    std::string serial;                // the dataset's sensor; empty: its first
    std::vector<std::string> objects;  // empty: every object the dataset holds
    std::vector<std::string> methods;  // select_study_methods()' names; empty: every method
    int max_k = 5;                     // combinations of 1..max_k settings (at least 2)
    int greedy_max = 12;               // greedy sequences up to this many settings
    int top = 10;                      // best pairs kept per metric
    // Called after each step (one method on one combination, for every
    // object) with the steps done and planned; the plan grows once, when the
    // greedy search starts. May throw to stop the study.
    std::function<void(std::size_t done, std::size_t total)> progress;
};

struct StudyResult {
    std::string backend;  // "vulkan (<device>)" or "cpu"
    std::vector<Illumination> settings;
    std::vector<std::string> objects;
    std::size_t static_setting = 0;       // index into settings: every LED at full level
    std::vector<Metrics> static_metrics;  // per object

    // A set of settings (indices into settings, ascending) and its gains,
    // averaged over the objects.
    struct Scored {
        std::vector<std::size_t> settings;
        Gains gain;
    };
    struct MethodSummary {
        std::string name;
        double improves_all_fraction = 0;  // of (combination, object) with 2+ settings
        Gains mean_gain;                   // over the same
        std::size_t fusions = 0;
    };
    std::vector<MethodSummary> methods;  // the methods studied, study_methods() order
    // Highest improves_all_fraction; among equal shares, the highest mean of
    // the three mean gains.
    std::string best_method;
    // The method pairs are ranked by and the greedy search and pairing use:
    // best_method, unless that is channel-sum (exactly three settings), then
    // the best of the methods taking any number.
    std::string ranking_method;
    // Per metric (kAllMetrics order), the `top` pairs of ranking_method by mean gain.
    std::array<std::vector<Scored>, 3> best_pairs;
    // Pairs among the top of all three metrics for one object, and for every object.
    std::vector<std::vector<std::vector<std::size_t>>> pairs_in_every_top_per_object;
    std::vector<std::vector<std::size_t>> pairs_in_every_top;
    // The static setting fused (ranking_method) with each other one.
    std::vector<Scored> pairing;
    // Per metric: the best single setting, then each step adds the setting
    // that raises the metric's mean gain most (ranking_method).
    struct Step {
        std::size_t n = 0;
        std::vector<std::size_t> sequence;  // in the order added
        double value = 0;                   // the metric's mean gain
    };
    std::array<std::vector<Step>, 3> greedy;
    // Per metric and object, how many settings the best combination of any
    // method has (1: a single frame beats every fusion).
    std::array<std::vector<std::size_t>, 3> best_k;
    // The combination (in fusion order) and method with the highest mean of
    // the three mean gains among those improving every metric on every object
    // (or, when none does, among all: improves_all_objects says which).
    Scored best;
    std::string best_best_method;
    bool best_improves_all_objects = false;

    std::size_t combinations = 0;  // settings combinations scored (per method and object)
    std::size_t fusions = 0;       // fused images scored, backgrounds excluded
    double seconds = 0;
};

// Runs the study on context's device, or on the CPU reference without one.
// Throws Error naming the dataset for a sensor, object or setting that is
// missing, a dataset without the static setting, frames too small for a
// method, or more combinations, objects or frames than a study takes (a
// dataset's size never chooses how much memory is used); and, before any
// frame is read, for options.methods that select_study_methods refuses.
StudyResult run_study(const Dataset& dataset, const StudyOptions& options, Context* context);

// What a study will take, known before any frame is captured: how many LED
// settings, which objects, and the frames' size.
struct StudyShape {
    std::size_t settings = 0;
    std::vector<std::string> objects;
    int height = 0;
    int width = 0;
};

// Everything run_study would refuse about a dataset of this shape under
// options, without the dataset: bad options, fewer than two or more settings
// than a study takes, an object named twice, more objects or frame bytes than
// a study holds, more combinations than it scores, frames too small for a
// selected method. Throws Error(InvalidArgument), the message starting with
// subject. run_study checks every dataset with it; `vkfuse tune` checks its
// capture with it before the first frame.
void check_study_shape(const StudyShape& shape, const StudyOptions& options, const std::string& subject);

}  // namespace vkfuse

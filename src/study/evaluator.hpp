// study/evaluator.hpp - scores one fusion of a study's frames for every object.
#pragma once
#include <memory>
#include <span>
#include <vector>

#include "study/study_data.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/study/study.hpp"
#include "vkfuse/vk/context.hpp"

namespace vkfuse::study {

// For one method and one combination of settings: the metrics of every
// object's fused image, its background being the same fusion of the
// settings' backgrounds. On the device, a multi-scale method (wavelet,
// Laplacian) decomposes every frame (the objects' and the backgrounds') once
// and fuses batches of combinations from those coefficients
// (study/cached_fusion.hpp) when asked for many (score_many); a single
// combination, the pointwise methods and a dataset too large for the cache
// run a plan per combination whose sensors are the objects, the fused
// background computed once for all of them (plans kept per method and
// settings count).
class Evaluator {
public:
    Evaluator(const StudyData& data, Context* context);  // no context: the CPU reference
    ~Evaluator();
    Evaluator(const Evaluator&) = delete;
    Evaluator& operator=(const Evaluator&) = delete;

    // combination: indices into data.settings, in fusion order. One setting
    // is no fusion: the frame is scored as it is, whatever the method. Always
    // through plans: a cache's batch would fuse one combination over and over
    // to fill its slots.
    std::vector<Metrics> score(const StudyMethod& method, std::span<const std::size_t> combination);
    // The same for each combination (all of one size, each in fusion order):
    // the way to fuse many, from the cache where the method has one.
    std::vector<std::vector<Metrics>> score_many(const StudyMethod& method,
                                                 std::span<const std::vector<std::size_t>> combinations);
    // How many combinations of size k score_many fuses at once for method:
    // a call with a multiple of it wastes no fusion.
    std::size_t batch(const StudyMethod& method, std::size_t k);

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse::study

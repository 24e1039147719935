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
// settings' backgrounds. On the device, the objects are the sensors of one
// plan (one submit per combination) and the fused background is computed
// once for all of them; plans are kept per (method, settings count).
class Evaluator {
public:
    Evaluator(const StudyData& data, Context* context);  // no context: the CPU reference
    ~Evaluator();
    Evaluator(const Evaluator&) = delete;
    Evaluator& operator=(const Evaluator&) = delete;

    // combination: indices into data.settings, in fusion order. One setting
    // is no fusion: the frame is scored as it is, whatever the method.
    std::vector<Metrics> score(const StudyMethod& method, std::span<const std::size_t> combination);

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse::study

#include "study/evaluator.hpp"

#include <algorithm>
#include <optional>
#include <string>

#include "study/cached_fusion.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::study {
namespace {

ImageD to_double(const Frame& f) {
    ImageD img(f.height, f.width, 3);
    for (std::size_t i = 0; i < img.size(); ++i) img.data[i] = double(f.pixels[i]) / 255.0;
    return img;
}

// The plans for one method and settings count: the backgrounds' fusion (one
// sensor, float input, the image read back) and the objects' (one sensor per
// object, 8-bit frames, metrics only).
struct PlanPair {
    std::string method;
    std::size_t k = 0;
    std::optional<Plan> backgrounds;
    Plan objects;
};

// Plans kept at once: a study walks combinations by size, so only the sizes
// in use (and the greedy search's) need theirs.
constexpr std::size_t kPlansKept = 16;
// The most device memory a study's decomposition may take (a QVGA study of
// 23 settings and 9 objects: about 1.1 GiB); beyond it, plans, which need
// far less.
constexpr std::uint64_t kMaxCacheBytes = std::uint64_t(2) << 30;

}  // namespace

struct Evaluator::Impl {
    const StudyData& data;
    Context* context;
    std::vector<PlanPair> plans;  // most recently used last
    // The coefficients of the last multi-scale method scored (sources: the
    // backgrounds, then each object; frames: the settings).
    std::string cached_method;
    std::unique_ptr<vk::CachedFusion> cached;

    vk::CachedFusionShape cache_shape(const StudyMethod& method) const {
        return {method.spec, data.height, data.width, 3, int(data.objects.size()) + 1, int(data.settings.size())};
    }
    bool uses_cache(const StudyMethod& method, std::size_t k) const {
        return context && k > 1 && vk::CachedFusion::supports(method.spec.method) &&
               vk::CachedFusion::cache_bytes(cache_shape(method)) <= kMaxCacheBytes;
    }
    vk::CachedFusion& cache_for(const StudyMethod& method) {
        if (cached && cached_method == method.name) return *cached;
        cached.reset();  // one cache at a time: a method's is rebuilt in well under a second
        std::vector<FrameView> images;
        for (const Image& b : data.backgrounds) images.push_back(FrameView::of(b));
        for (const auto& object : data.frames)
            for (const Frame& f : object) images.push_back(f.view());
        cached = std::make_unique<vk::CachedFusion>(*context, cache_shape(method), images);
        cached_method = method.name;
        return *cached;
    }

    PlanConfig config(const StudyMethod& method, std::size_t k, int sensors) const {
        PlanConfig c;
        c.fusion = method.spec;
        c.fuse = k > 1;
        c.height = data.height;
        c.width = data.width;
        c.channels = 3;
        c.frames = int(k);
        c.sensors = sensors;
        return c;
    }

    PlanPair& plans_for(const StudyMethod& method, std::size_t k) {
        const std::string key = k > 1 ? method.name : std::string("single");
        auto it = std::find_if(plans.begin(), plans.end(), [&](const PlanPair& p) { return p.method == key && p.k == k; });
        if (it != plans.end()) {
            std::rotate(it, it + 1, plans.end());
            return plans.back();
        }
        if (plans.size() == kPlansKept) plans.erase(plans.begin());
        PlanConfig objects = config(method, k, int(data.objects.size()));
        objects.input = PixelType::U8;
        objects.want_fused = false;
        objects.metrics = MetricSet::all();
        std::optional<Plan> backgrounds;
        if (k > 1) {
            PlanConfig bg = config(method, k, 1);
            bg.input = PixelType::F32;
            bg.metrics = {};
            backgrounds.emplace(*context, bg);
        }
        plans.push_back(PlanPair{key, k, std::move(backgrounds), Plan(*context, objects)});
        return plans.back();
    }

    std::vector<Metrics> on_device(const StudyMethod& method, std::span<const std::size_t> combination) {
        PlanPair& p = plans_for(method, combination.size());
        FrameView background = FrameView::of(data.backgrounds[combination[0]]);
        if (p.backgrounds) {
            std::vector<FrameView> views;
            for (std::size_t s : combination) views.push_back(FrameView::of(data.backgrounds[s]));
            p.backgrounds->run(views);
            background = FrameView::of(p.backgrounds->fused(0));
        }
        std::vector<FrameView> frames;
        for (std::size_t o = 0; o < data.objects.size(); ++o) {
            p.objects.set_background(int(o), background);
            for (std::size_t s : combination) frames.push_back(data.frames[o][s].view());
        }
        p.objects.run(frames);
        std::vector<Metrics> out;
        for (std::size_t o = 0; o < data.objects.size(); ++o) out.push_back(p.objects.metrics(int(o)));
        return out;
    }

    std::vector<Metrics> on_cpu(const StudyMethod& method, std::span<const std::size_t> combination) {
        std::vector<ImageD> backgrounds;
        for (std::size_t s : combination) backgrounds.push_back(convert<double>(data.backgrounds[s]));
        const ImageD background =
            combination.size() > 1 ? fuse_reference(backgrounds, method.spec) : std::move(backgrounds.front());
        std::vector<Metrics> out;
        for (std::size_t o = 0; o < data.objects.size(); ++o) {
            std::vector<ImageD> frames;
            for (std::size_t s : combination) frames.push_back(to_double(data.frames[o][s]));
            const ImageD image = combination.size() > 1 ? fuse_reference(frames, method.spec) : std::move(frames.front());
            out.push_back(metrics_reference(image, &background));
        }
        return out;
    }
};

Evaluator::Evaluator(const StudyData& data, Context* context) : impl_(new Impl{data, context, {}, {}, {}}) {}
Evaluator::~Evaluator() = default;

std::vector<Metrics> Evaluator::score(const StudyMethod& method, std::span<const std::size_t> combination) {
    return impl_->context ? impl_->on_device(method, combination) : impl_->on_cpu(method, combination);
}

std::size_t Evaluator::batch(const StudyMethod& method, std::size_t k) {
    return impl_->uses_cache(method, k) ? impl_->cache_for(method).batch() : 1;
}

std::vector<std::vector<Metrics>> Evaluator::score_many(const StudyMethod& method,
                                                        std::span<const std::vector<std::size_t>> combinations) {
    if (!combinations.empty() && impl_->uses_cache(method, combinations.front().size()))
        return impl_->cache_for(method).score(combinations);
    std::vector<std::vector<Metrics>> out;
    for (const auto& c : combinations) out.push_back(score(method, c));
    return out;
}

}  // namespace vkfuse::study

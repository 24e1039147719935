#include "vk_fixture.hpp"

#include <algorithm>
#include <cstdio>

namespace vkfuse::test {

ValidationLog& validation_log() {
    static ValidationLog log;
    return log;
}

bool validation_available() {
    static const bool installed = [] {
        const bool found = validation_layer_installed();
        if (!found)
            std::fprintf(stderr, "vkfuse tests: VK_LAYER_KHRONOS_validation is not installed: Vulkan tests run "
                                 "without validation (install vulkan-validationlayers to check them)\n");
        return found;
    }();
    return installed;
}

ContextOptions validated_options() {
    ContextOptions o;
    o.validation = validation_available();
    // lavapipe runs a submit's dispatches in order: only the layer's
    // synchronization validation shows a barrier a GPU would need.
    o.synchronization_validation = o.validation;
    o.on_validation_message = [](const std::string& m) {
        auto& log = validation_log();
        std::lock_guard lock(log.mutex);
        log.messages.push_back(m);
    };
    return o;
}

Context& shared_context() {
    static Context ctx(validated_options());
    return ctx;
}

Context& addressed_context() {
    static Context ctx([] {
        ContextOptions o = validated_options();
        o.device_addresses_only = true;
        return o;
    }());
    return ctx;
}

Context& bound_context() {
    static Context ctx([] {
        ContextOptions o = validated_options();
        o.kernel_buffers = KernelBuffers::Bound;
        return o;
    }());
    return ctx;
}

bool has_device_addresses() { return shared_context().device().device_addresses; }

double module_ulps(const Context& context) { return context.device().type == "cpu" ? 0 : kModuleUlps; }

std::string arithmetic_name(const Context& context) {
    return std::string(to_string(context.filter_arithmetic())) + (context.splits_products() ? ", split products" : "");
}

std::vector<Context*> filter_arithmetic_contexts() {
    Context& shared = shared_context();
    const bool shared_is_float64 = shared.filter_arithmetic() == FilterArithmetic::Float64;
    std::vector<Context*> contexts{&shared};
    if (shared_is_float64 || shared.device().float64) {
        static Context other = [&] {
            ContextOptions o = validated_options();
            o.device_index = shared.device().index;
            o.filter_arithmetic = shared_is_float64 ? FilterArithmetic::CompensatedFloat32 : FilterArithmetic::Float64;
            return Context(o);
        }();
        contexts.push_back(&other);
    }
    // lavapipe's fma is not fused: its compensated context splits already.
    if (std::none_of(contexts.begin(), contexts.end(), [](Context* c) { return c->splits_products(); })) {
        static Context split = [&] {
            ContextOptions o = validated_options();
            o.device_index = shared.device().index;
            o.filter_arithmetic = FilterArithmetic::CompensatedFloat32;
            o.split_products = true;
            return Context(o);
        }();
        contexts.push_back(&split);
    }
    return contexts;
}

void VulkanTest::SetUp() {
    shared_context();
    std::lock_guard lock(validation_log().mutex);
    messages_before_ = validation_log().messages.size();
}

void VulkanTest::TearDown() {
    std::lock_guard lock(validation_log().mutex);
    auto& all = validation_log().messages;
    for (std::size_t i = messages_before_; i < all.size(); ++i) ADD_FAILURE() << "Vulkan validation: " << all[i];
}

Plan run_plan(Context& ctx, const PlanConfig& cfg, const std::vector<Image>& frames) {
    Plan plan(ctx, cfg);
    std::vector<FrameView> views;
    for (const auto& f : frames) views.push_back(FrameView::of(f));
    plan.run(views);
    return plan;
}

}  // namespace vkfuse::test

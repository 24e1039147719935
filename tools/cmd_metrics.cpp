// vkfuse metrics: score each input image, one JSON object per line.
#include <array>
#include <cstdio>
#include <map>
#include <new>
#include <optional>

#include "shared_options.hpp"
#include "commands.hpp"
#include "standard_output.hpp"
#include "inputs.hpp"
#include "memory_check.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--background", "", "BG", "also report the mean |IN - BG| (BG must have each input's shape)"},
    kBackendOption,
};

constexpr CommandSpec kSpec{
    "metrics",
    "print sharpness, RMS contrast (and background difference) of images as JSON lines",
    "vkfuse metrics [--background BG] [--backend B] IN...",
    "Prints one JSON object per input, in order, one per line:\n"
    "  {\"image\": PATH, \"sharpness\": S, \"contrast\": C, \"background_diff\": D}\n"
    "S is the mean gradient magnitude of the luma, C its population standard deviation,\n"
    "D (only with --background) the mean |IN - BG| over pixels and channels. Every input\n"
    "is checked before anything is printed.",
    kOptions,
    "vkfuse metrics --background bg.png fused.npy red.png",
};

std::vector<Metrics> metrics_on_cpu(const std::vector<Input>& inputs, const Input* background) {
    std::optional<ImageD> bg;
    if (background) bg = convert<double>(background->image);
    std::vector<Metrics> out;
    for (const Input& in : inputs) out.push_back(metrics_reference(convert<double>(in.image), bg ? &*bg : nullptr));
    return out;
}

PlanConfig metrics_plan(const Image& shape, bool background_diff) {
    PlanConfig config;
    config.fuse = false;
    config.height = shape.height;
    config.width = shape.width;
    config.channels = shape.channels;
    config.frames = 1;
    config.sensors = 1;
    config.input = PixelType::F32;
    config.want_fused = false;
    config.metrics = MetricSet::all().with(Metric::BackgroundDiff, background_diff);
    return config;
}

// One plan per distinct input shape, built the first time that shape appears.
std::vector<Metrics> metrics_on_vulkan(Context& context, const std::vector<Input>& inputs, const Input* background) {
    std::map<std::array<int, 3>, Plan> plans;
    std::vector<Metrics> out;
    for (const Input& in : inputs) {
        std::array<int, 3> key{in.image.height, in.image.width, in.image.channels};
        auto it = plans.find(key);
        if (it == plans.end()) {
            it = plans.try_emplace(key, context, metrics_plan(in.image, background != nullptr)).first;
            if (background) it->second.set_background(0, FrameView::of(background->image));
        }
        FrameView frame = FrameView::of(in.image);
        it->second.run(std::span(&frame, 1));
        out.push_back(it->second.metrics(0));
    }
    return out;
}

std::string json_line(const std::string& path, const Metrics& m) {
    std::string line = "{\"image\": " + json_string(path) + ", \"sharpness\": " + json_number(m.sharpness) +
                       ", \"contrast\": " + json_number(m.contrast);
    if (m.background_diff) line += ", \"background_diff\": " + json_number(*m.background_diff);
    return line + "}\n";
}

int run(const Args& args) {
    Backend backend = parse_backend_option(args.value("--backend").value_or("auto"));
    if (args.operands().empty()) args.usage_error("no input images");
    // Headers first: a bad input, a background of another shape or more
    // memory than the process can take is reported before any pixel is decoded.
    const std::vector<InputHeader> headers = read_headers(args.operands());
    std::optional<InputHeader> background_header;
    std::vector<std::string> everything = args.operands();
    if (auto path = args.value("--background")) {
        background_header = read_headers({*path}).front();
        everything.push_back(*path);
    }
    if (background_header)
        for (const InputHeader& in : headers) require_same_shape(in, *background_header, "the background ");
    std::vector<io::ImageHeader> shapes;
    for (const InputHeader& in : headers) shapes.push_back(in.header);
    const std::uint64_t need =
        metrics_memory_need(shapes, background_header ? &background_header->header : nullptr, backend);
    require_memory(everything, "scoring", need);

    std::string text;
    try {
        std::vector<Input> inputs = read_inputs(args.operands());
        std::optional<Input> background;
        if (background_header) background = read_inputs({background_header->path}).front();
        if (background)
            for (const Input& in : inputs) require_same_shape(in, *background, "the background ");

        std::optional<Context> context = open_backend(backend);
        const Input* bg = background ? &*background : nullptr;
        std::vector<Metrics> metrics = context ? metrics_on_vulkan(*context, inputs, bg) : metrics_on_cpu(inputs, bg);
        for (std::size_t i = 0; i < inputs.size(); ++i) text += json_line(inputs[i].path, metrics[i]);
    } catch (const std::bad_alloc&) {
        out_of_memory(everything, "scoring", need);
    }
    // Printed only once every input has been scored: a failure leaves stdout empty.
    print_checked(text);
    return 0;
}

}  // namespace

const Command metrics_command{kSpec, run};

}  // namespace vkfuse::cli

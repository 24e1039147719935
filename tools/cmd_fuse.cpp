// vkfuse fuse: read K frames, fuse them on the chosen backend, write one image.
#include <new>
#include <span>

#include "shared_options.hpp"
#include "commands.hpp"
#include "core/check_finite.hpp"
#include "inputs.hpp"
#include "io/interrupt_cleanup.hpp"
#include "memory_check.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/vk/plan.hpp"

namespace vkfuse::cli {
namespace {

constexpr OptionSpec kOptions[] = {
    {"--method", "", "M", "{methods} (required)"},
    kLevelsOption,
    kWaveletOption,
    kModeOption,
    kBaseRuleOption,
    kDetailRuleOption,
    kBackendOption,
    {"-o", "--output", "OUT", "output image, .npy (float32, unclamped) or .png (8-bit, clamped) (required)"},
};

constexpr CommandSpec kSpec{
    "fuse",
    "fuse several frames of one scene (one per LED lighting) into one image",
    "vkfuse fuse --method M [options] -o OUT IN...",
    "Fuses the frames IN... (.png or .npy, all of one shape) with method M and writes\n"
    "the result to OUT. channel-sum takes exactly 3 RGB frames (R from the first, G\n"
    "from the second, B from the third). OUT is written only when everything succeeded.",
    kOptions,
    "vkfuse fuse --method wavelet --levels 3 --wavelet bior4.4 -o fused.npy red.png green.png blue.png",
};

// The reference fuses in double; a result past float32's range (pyramids and
// wavelets overshoot inputs near FLT_MAX) cannot be stored and is an error,
// as on the Vulkan path, never an Inf in the output.
Image fuse_on_cpu(const FusionSpec& spec, const std::vector<Input>& inputs) {
    std::vector<ImageD> frames;
    frames.reserve(inputs.size());
    for (const Input& in : inputs) frames.push_back(convert<double>(in.image));
    const ImageD fused = fuse_reference(frames, spec);
    core::require_float32_range(fused, "fused");
    return convert<float>(fused);
}

Image fuse_on_vulkan(Context& context, const FusionSpec& spec, const std::vector<Input>& inputs) {
    const Image& first = inputs.front().image;
    PlanConfig config;
    config.fusion = spec;
    config.height = first.height;
    config.width = first.width;
    config.channels = first.channels;
    config.frames = int(inputs.size());
    config.sensors = 1;
    config.input = PixelType::F32;
    config.want_fused = true;
    config.metrics = {};
    Plan plan(context, config);
    std::vector<FrameView> views;
    for (const Input& in : inputs) views.push_back(FrameView::of(in.image));
    plan.run(views);
    return plan.fused(0);
}

int run(const Args& args) {
    FusionSpec spec;
    spec.method = parse_method(args.required("--method"));
    spec = fusion_options(args, spec);
    std::string output = args.required("-o");
    Backend backend = parse_backend_option(args.value("--backend").value_or("auto"));
    if (args.operands().empty()) args.usage_error("no input images");
    io::check_image_extension(output);  // fail before the work, not after it

    // Headers first: a bad input, mismatched shapes, an impossible level count
    // or more memory than the process can take is reported before any pixel
    // is decoded.
    const std::vector<InputHeader> headers = read_headers(args.operands());
    for (const InputHeader& in : headers) require_same_shape(in, headers.front());
    const io::ImageHeader& shape = headers.front().header;
    validate(spec, shape.height, shape.width, shape.channels, int(headers.size()));
    std::vector<io::ImageHeader> shapes;
    for (const InputHeader& in : headers) shapes.push_back(in.header);
    const std::uint64_t need = fuse_memory_need(shapes, spec.method, backend);
    require_memory(args.operands(), "fusing", need);

    // A SIGINT/SIGTERM while the output is written leaves no temporary behind.
    io::install_interrupt_cleanup();
    try {
        std::vector<Input> inputs = read_inputs(args.operands());
        for (const Input& in : inputs) require_same_shape(in, inputs.front());  // a file replaced meanwhile
        std::optional<Context> context = open_backend(backend);
        Image fused = context ? fuse_on_vulkan(*context, spec, inputs) : fuse_on_cpu(spec, inputs);
        io::write_image(output, fused);
    } catch (const std::bad_alloc&) {
        out_of_memory(args.operands(), "fusing", need);
    }
    return 0;
}

}  // namespace

const Command fuse_command{kSpec, run};

}  // namespace vkfuse::cli

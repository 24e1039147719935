#include "driver.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

#include "backends.hpp"
#include "floor_model.hpp"
#include "matrix.hpp"
#include "options.hpp"
#include "peer.hpp"
#include "report.hpp"
#include "pipeline.hpp"
#include "scenes.hpp"
#include "windows.hpp"
#include "timing.hpp"
#include "vk/probes/copy_bandwidth.hpp"
#include "vk/probes/kernel_access.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::bench {
namespace {

#ifdef VKFUSE_BENCH_CPP_PEER
constexpr const char* kCppPeer = VKFUSE_BENCH_CPP_PEER;
#else
constexpr const char* kCppPeer = "";  // OpenCV was not found: PeerRunner::program says so
#endif

// What vkfuse-bench runs beside it: installed, at <prefix>/<installed> (the
// program being <prefix>/bin/vkfuse-bench); else where the build put it.
std::string beside_program(const char* installed, const char* built) {
    std::error_code ec;
    const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec && *built) {
        const std::filesystem::path path = program.parent_path().parent_path() / installed;
        if (std::filesystem::exists(path, ec)) return path.string();
    }
    return built;
}

// What the run found once, before the first cell.
struct Environment {
    std::optional<Context> vulkan;
    std::string no_vulkan;  // why vulkan is empty
    std::string no_access;  // why access is empty
    std::optional<vk::CopyBandwidth> copy;
    std::optional<vk::KernelAccess> access;
    std::optional<Timing> empty_cycle;  // time_empty_cycle: the fixed cost every cell pays
    std::optional<PeerRunner> peers;
    std::optional<PeerRunner> cpp_peer;  // bench/peers/opencv_peer.cpp
    std::string peer_script, cpp_peer_program;  // where they are, installed or built
};

bool wants_vulkan(const Options& o, const std::vector<Cell>& cells) {
    if (o.probe) return true;
    for (const auto& c : cells)
        if (c.backend == Backend::Vulkan && c.skip.empty()) return true;
    return false;
}

// Large enough that a GPU's launch cost does not hide its memory speed, small
// enough that lavapipe measures in a second or two (--quick: a fraction).
std::uint64_t probe_bytes(const Options& o, const Context& vulkan) {
    const std::uint64_t mib = vulkan.device().type == "cpu" ? 16 : 256;
    return (o.scope == Scope::Quick ? mib / 4 : mib) << 20;
}

Environment discover(const Options& o, const std::vector<Cell>& cells) {
    Environment env;
    if (wants_vulkan(o, cells)) {
        try {
            ContextOptions co;
            co.device_index = o.device;
            env.vulkan.emplace(co);
            // --quick keeps the copy small: it runs in ctest on every build.
            const std::uint64_t bytes = std::uint64_t(o.scope == Scope::Quick ? 16 : 64) << 20;
            env.copy = vk::measure_copy_bandwidth(*env.vulkan, bytes);
        } catch (const Error& e) {
            // A bad VKFUSE_* setting is the user's to fix, not a missing device.
            if (e.kind() == ErrorKind::InvalidArgument) throw UsageError(e.what());
            env.no_vulkan = e.what();
            env.vulkan.reset();
        }
        // A failed probe is reported; the cells still run and check themselves.
        if (env.vulkan) try {
                env.access = vk::measure_kernel_access(*env.vulkan, probe_bytes(o, *env.vulkan));
            } catch (const std::exception& e) {
                env.no_access = e.what();
            }
        // Enough runs for a stable median of a sub-millisecond cycle.
        if (env.vulkan) try {
                env.empty_cycle = time_empty_cycle(*env.vulkan, {5, o.scope == Scope::Quick ? 50 : 300});
            } catch (const Error&) {  // the cells then say what fails; the floor leaves the fixed cost out
            }
    }
    if (o.peers && !o.probe) {
        env.peer_script = beside_program(VKFUSE_BENCH_INSTALLED_PEER_SCRIPT, VKFUSE_BENCH_PEER_SCRIPT);
        env.cpp_peer_program = beside_program(VKFUSE_BENCH_INSTALLED_CPP_PEER, kCppPeer);
        env.peers.emplace(env.peer_script, o.python);
        env.cpp_peer =
            PeerRunner::program(env.cpp_peer_program, {Method::ChannelSum, Method::Brovey, Method::Laplacian});
    }
    return env;
}

// The device's floor: what every kernel pays per access, per flop, per dispatch.
void print_kernel_access(const vk::KernelAccess& a) {
    std::printf("kernel access: %.3g ns per float copied via device addresses, %.3g as address vec4, %.3g via "
                "bound buffers, %.3g as bound vec4 (%llu floats, %s)\n",
                a.address_ns, a.address_vec4_ns, a.bound_ns, a.bound_vec4_ns, static_cast<unsigned long long>(a.floats),
                a.device_timed ? "device timestamps" : "host clock");
    std::printf("kernel compute: %.3g ns per shared-memory exchange (store, barrier, load, barrier), %.3g GFLOP/s "
                "multiply-add, %.3g us per small dispatch\n",
                a.shared_exchange_ns, a.fma_gflops, a.dispatch_us);
}

// The Vulkan device and what it measured at start (all of --probe's output).
void print_device(const Environment& env) {
    if (env.vulkan) {
        const auto& d = env.vulkan->device();
        std::printf("vulkan: %s (%s, %s, Vulkan %s)\n", d.name.c_str(), d.type.c_str(), d.driver.c_str(),
                    d.api_version.c_str());
        if (env.copy)
            std::printf("copy bandwidth: %.2f GB/s (%llu MiB buffer copy, %s)\n", env.copy->bytes_per_second() * 1e-9,
                        static_cast<unsigned long long>(env.copy->bytes >> 20),
                        env.copy->device_timed ? "device timestamps" : "host clock");
        if (env.access)
            print_kernel_access(*env.access);
        else
            std::printf("kernel access: probe failed (%s)\n", env.no_access.c_str());
        if (env.empty_cycle)
            std::printf("cycle fixed cost: %.3g ms median, %.3g min of %d (a 4x4 plan's cycle: frames in, one small "
                        "dispatch, submit, wait, image out)\n",
                        env.empty_cycle->median_ms, env.empty_cycle->min_ms, env.empty_cycle->runs);
    } else if (!env.no_vulkan.empty()) {
        std::printf("vulkan: not available (%s); vulkan cells are skipped\n", env.no_vulkan.c_str());
    }
}

void print_environment(const Environment& env, const Options& o, double budget) {
    print_device(env);
    if (!o.peers)
        std::printf("peers: off (--no-peers)\n");
    else if (env.peers->available())
        std::printf("peers: %s %s\n", env.peers->python().c_str(), env.peer_script.c_str());
    else
        std::printf("peers: not available (%s); peer columns stay empty\n", env.peers->why_not().c_str());
    if (o.peers && env.cpp_peer->available())
        std::printf("C++ peer: %s (%s)\n", env.cpp_peer_program.c_str(), env.cpp_peer->methods().c_str());
    else if (o.peers)
        std::printf("C++ peer: %s\n", env.cpp_peer->why_not().c_str());
    const bool fp16 = env.vulkan && env.vulkan->device().fp16_storage;
    std::printf("precision: fp32 (fp16 storage %s; --precision fp16 or --full adds its cells); memory limit %.1f GiB\n",
                fp16 ? "supported" : "not supported by the device", budget / (1024.0 * 1024.0 * 1024.0));
    std::printf("host: %u CPUs, load average %.2f at start (other processes share what is timed)\n\n",
                std::thread::hardware_concurrency(), load_average());
}

RunPolicy policy_for(const Options& o, const Cell& c, const Environment& env) {
    const bool cpu_device = env.vulkan && env.vulkan->device().type == "cpu";
    return {o.warmup, o.runs, o.cell_seconds, c.backend == Backend::Cpu || cpu_device};
}

// A cell that is not measured still names the device it was meant for.
CellResult unmeasured(const Cell& c, const Environment& env) {
    CellResult r;
    r.cell = c;
    r.device = c.backend == Backend::Cpu ? kCpuDevice : env.vulkan ? env.vulkan->device().name : "";
    if (c.backend == Backend::Vulkan && env.vulkan) r.driver = env.vulkan->device().driver;
    return r;
}

CellResult measure(Environment& env, const Options& o, const Cell& c, const Inputs& in,
                   const std::vector<Expected>& expected) {
    CellResult r;
    const double load = load_average();
    try {
        r = c.backend == Backend::Cpu ? measure_cpu(c, in, expected, policy_for(o, c, env))
                                      : measure_vulkan(*env.vulkan, c, in, expected, policy_for(o, c, env), o.profile);
    } catch (const Error& e) {  // out of device memory, device lost: this cell fails, the run goes on
        r = unmeasured(c, env);
        r.failure = e.what();
    }
    if (c.backend == Backend::Vulkan && env.copy) r.copy_bandwidth = env.copy->bytes_per_second();
    if (c.backend == Backend::Vulkan && env.access) {
        r.kernel_copy_ns = env.access->device_addresses ? env.access->address_ns : env.access->bound_ns;
        r.cycle_fixed_ms = env.empty_cycle ? std::optional(env.empty_cycle->median_ms) : std::nullopt;
        // The bench uploads float32 frames.
        r.floor_ms = floor_ms(ideal_pipeline(c, false), *env.access, r.cycle_fixed_ms.value_or(0));
    }
    r.load_average = load;
    return r;
}

void report(CellResult r, std::vector<CellResult>& out) {
    print_row(stdout, r);
    std::fflush(stdout);
    out.push_back(std::move(r));
}

// The cells of one workload (same inputs, different backends).
void run_workload(Environment& env, const Options& o, std::vector<Cell> cells, std::vector<CellResult>& out) {
    for (auto& c : cells) {
        if (c.backend != Backend::Vulkan || !c.skip.empty()) continue;
        if (!env.vulkan)
            c.skip = "no Vulkan device";
        else if (c.precision == Precision::Fp16Storage && !env.vulkan->device().fp16_storage)
            c.skip = "fp16 storage: " + env.vulkan->device().name + " lacks 16-bit storage buffers or float16 shaders";
    }
    const bool any = std::any_of(cells.begin(), cells.end(), [](const Cell& c) { return c.skip.empty(); });
    if (!any) {
        for (const auto& c : cells) report(unmeasured(c, env), out);
        return;
    }
    const Cell& first = cells.front();
    const Inputs in(first.size, first.frames, first.sensors);
    const std::vector<Expected> expected = expected_results(in, first.fusion());
    std::optional<PeerResult> peer;
    if (env.peers && env.peers->available()) peer = env.peers->run(first, in, expected.front(), o.cell_seconds, o.runs);
    std::optional<PeerResult> cpp_peer;
    if (env.cpp_peer && env.cpp_peer->available() && env.cpp_peer->runs(first))
        cpp_peer = env.cpp_peer->run(first, in, expected.front(), o.cell_seconds, o.runs);
    for (const auto& c : cells) {
        CellResult r = c.skip.empty() ? measure(env, o, c, in, expected) : unmeasured(c, env);
        if (r.measured()) {
            r.peer = peer;
            r.cpp_peer = cpp_peer;
        }
        report(std::move(r), out);
    }
    if (peer) print_peer(stdout, *peer);
    if (cpp_peer) print_peer(stdout, *cpp_peer);
}

void print_cells(const std::vector<Cell>& cells) {
    for (const auto& c : cells)
        std::printf("%-40s ~%8.3f GiB  %s\n", c.describe().c_str(), estimated_bytes(c) / (1024.0 * 1024.0 * 1024.0),
                    c.skip.empty() ? "" : ("skipped: " + c.skip).c_str());
    std::printf("%zu cells\n", cells.size());
}

void check_output_dir(const std::string& option, const std::string& path) {
    if (path.empty()) return;
    const auto dir = std::filesystem::absolute(path).parent_path();
    if (!std::filesystem::is_directory(dir))
        throw UsageError(option + " " + path + ": directory " + dir.string() + " does not exist");
}

}  // namespace

int run_bench(const Options& o) {
    check_output_dir("--json", o.json_path);
    check_output_dir("--plot", o.plot_path);
    if (o.scenes) return run_scenes(o);
    if (o.windows) return run_windows(o);
    if (o.pipeline) return run_pipeline(o);
    const double budget = memory_budget(o.mem_limit_gib);
    const std::vector<Cell> cells = build_matrix(o, budget);
    if (o.list) {
        print_cells(cells);
        return 0;
    }
    Environment env = discover(o, cells);
    if (o.probe) {
        if (!env.vulkan) throw Error(ErrorKind::Device, "--probe: no usable Vulkan device (" + env.no_vulkan + ")");
        print_device(env);
        return env.access ? 0 : 1;
    }
    print_environment(env, o, budget);
    print_table_header(stdout);
    std::vector<CellResult> results;
    for (std::size_t i = 0; i < cells.size();) {
        std::size_t j = i + 1;
        while (j < cells.size() && cells[j].same_workload(cells[i])) ++j;
        run_workload(env, o, std::vector<Cell>(cells.begin() + long(i), cells.begin() + long(j)), results);
        i = j;
    }
    print_summary(stdout, results);
    if (!o.json_path.empty()) write_json(o.json_path, results);
    if (!o.plot_path.empty()) write_plot(o.plot_path, results, env.vulkan ? env.vulkan->device().name : "no Vulkan device");
    return 0;
}

}  // namespace vkfuse::bench

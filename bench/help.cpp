#include "options.hpp"

#include "core/method_table.hpp"

namespace vkfuse::bench {

std::string help_text() {
    return core::with_method_names(R"(usage: vkfuse-bench [--quick | --full] [filters] [--json FILE.json] [--plot FILE.svg] [options]

Run time against error of vkfuse's fusion (+ sharpness, contrast and background
difference, fused image read back) per cell of the matrix
  method x backend x precision x resolution x K frames x S sensors,
side by side with the paper-style Python pipelines (PyWavelets, OpenCV, numpy)
run on the same synthetic tactile frames.

Scopes:
  (default)   every method at QVGA and VGA, K=3, S=1 on both backends; S=8, 64
              at QVGA on vulkan for brovey, laplacian and wavelet/bior4.4; K=2, 5
              at QVGA for laplacian and wavelet/bior4.4 (about 2 minutes on an
              idle 2-core lavapipe host).
              With any axis filter the default becomes one block: the given axes
              with QVGA, K=3, S=1, every method and both backends for the rest.
  --quick     seconds: channel-sum, brovey, laplacian, wavelet/bior4.4 at 160x120,
              K=3, S=1 and 2, vulkan also in fp16 (the ctest smoke run; filters
              replace its axes).
  --full      every cell: 7 methods x 2 backends x 4 sizes x K 2,3,5 x S 1,8,64,
              vulkan in fp32 and fp16 (hours on lavapipe).
  Only --quick and --full have fp16 cells unless --precision asks for them.

Filters (comma lists; each replaces that axis of the scope):
  --method M        {methods}
  --wavelet W       haar, db2, bior2.2, bior4.4 (alone it implies --method wavelet)
  --backend B       cpu (double-precision reference), vulkan
  --precision P     fp32, fp16 (float16 planes between kernels, float32 arithmetic;
                    vulkan only, where the device has 16-bit storage). The cpu
                    reference computes in double: "fp64" in reports, run with fp32
  --size WxH        e.g. 320x240, or qvga, vga, 1080p, 4k (4096x4096)
  --frames K        2..16 (channel-sum exists for K=3 only)
  --sensors S       1..4096
  --levels L        pyramid levels for laplacian/wavelet (default 4 / 3)

Output:
  --json FILE.json  an array with one object per cell: method, wavelet, levels,
                    backend, device, driver, precision, width, height, frames, sensors,
                    skipped, median_ms, min_ms, max_ms, runs, runs_capped, plan_ms,
                    throughput_cycles_s (sensor-cycles/s), mpixels_s, max_abs_err,
                    mean_abs_err, samples_over_1e-5, checked_sensors,
                    metric_rel_err{sharpness, contrast, background_diff}, kernel_ms,
                    bytes_per_cycle, copy_bandwidth_gbs, bandwidth_fraction,
                    kernel_copy_ns_per_float, cycle_fixed_ms (an empty cycle:
                    what every cycle pays on this device), floor_ms (the ideal pipeline for the
                    cell at this device's probed costs), floor_fraction
                    (floor_ms / median_ms), peer, peer_failure, peer_median_ms,
                    peer_ms_per_sensor, peer_runs, peer_max_abs_err,
                    peer_mean_abs_err, peer_metric_rel_err,
                    peer_speedup (peer_median_ms / median_ms); for Laplacian,
                    Brovey and channel-sum cells the OpenCV C++ pipeline, the
                    same fields prefixed cpp_peer (cpp_peer, cpp_peer_failure,
                    cpp_peer_median_ms, ..., cpp_peer_speedup)
  --plot FILE.svg   log-log time per sensor-cycle against max abs error,
                    coloured by method, marked by backend and precision and
                    peer (Python, OpenCV C++); each point numbered by its
                    workload, with the workloads' times and errors in a table
                    under the plot
  --profile         per-stage GPU times from Plan::profile() (median over runs)

Measurement:
  --runs N          timed cycles per cell (default 20) after --warmup N (default 2).
                    On the CPU reference, and on a Vulkan device that is a CPU
                    (lavapipe), a cell whose runs would exceed --cell-seconds T
                    (default 60) gets fewer runs, never under 3 (marked * / runs_capped).
  --device N        Vulkan device index (default: the best usable one)
  --mem-limit GiB   skip cells estimated to need more (default 80% of available memory)
  --no-peers        do not run the peers (Python, and the OpenCV C++ one)
  --python PATH     the peers' interpreter (default /usr/bin/python3, then python3)
  --list            print the cells (with estimated memory and skip reasons), run nothing
  --probe           measure the Vulkan device only (copy bandwidth, kernel access
                    costs), print the device lines, run no cell and no peer
  --scenes          skipping instead of the matrix: simulated scenes (none: no
                    contact; small: a ball pressed 0.1 mm, about 5% of the tiles;
                    ball: 0.3 mm; coin; slide: the ball sliding), 24 cycles each at
                    QVGA, K=3 (15,15,15+0,15,0+15,0,0), wavelet bior4.4 L3, run
                    with skip off, idle, static and tiles at thresholds 4, 8 and 16,
                    round robin;
                    a row per scene and setting: scene, skip, threshold,
                    contact_fraction (tiles changed at the default threshold),
                    fused_fraction, median_ms, full_median_ms (skip off, same
                    scene), time_fraction, max_abs_err_contact (what was fused,
                    against full fusion), max_abs_err_outside (the rest: skipped
                    cycles, idle or reused, and outside a tiles cycle's fused
                    region), tiles_work_fraction (the tile-sparse work model).
                    --json writes the rows, --plot time against error per scene;
                    --runs N: N cycles, rounded up to whole passes over the 24
  --windows         sliding windows against cycles instead of the matrix: one
                    simulated DIGIT (QVGA, 60 fps, LED latency 1.5 frames) pressed
                    by a coin that is still, taps or slides (periods 0.5, 1, 2 s),
                    4 s of sensor time per row, K=2 (15,15,15+0,15,0) and K=3
                    (15,0,0+0,15,0+0,0,15; --frames picks), wavelet bior4.4 L3;
                    a row per scene, window and K: fused_fps (per second of sensor
                    time), latency_mean_ms / latency_max_ms (from the first frame
                    showing a contact change to the end of the newest frame of the
                    first image fused with it), span_max_ms (the widest window),
                    max_abs_err / mean_abs_err and the metrics' relative errors
                    against fusing every setting at one instant (each slot's frame
                    rendered again with its own noise and the newest frame's
                    contact). --json writes the rows, --plot fused rate against error
  --pipeline        a sensor loop instead of the matrix: S sensors (default 16; the
                    first --sensors), QVGA (the first --size), K=3 (the first
                    --frames), 8-bit frames, every fused image and metric read
                    back, for brovey, laplacian and wavelet/bior4.4 (or --method),
                    on vulkan: each cycle a round trip (Plan::run) against two
                    cycles in flight (submit c+1, collect c, read c while c+1
                    runs), 5 alternating blocks of --runs cycles each; a row per
                    method and way: method, levels, device, width, height,
                    frames, sensors, cycles_in_flight, median_ms (per cycle),
                    throughput_cycles_s, speedup (over the round trip),
                    max_abs_diff (pipelined results against the round trip's:
                    0, or exit status 1)

How it measures:
  A cycle is what a sensor loop does: Plan::run on all S*K frames (upload,
  fusion, metrics), then fused() and metrics() of every sensor. The CPU reference
  runs fuse_reference + metrics_reference sensor after sensor. Errors are those
  of the last cycle against the double reference on the same inputs, over up to
  4 sensors (first, last, two between). Inputs are deterministic synthetic DIGIT-
  like frames (gel illumination per LED, a pressed textured object, noise);
  beyond 8 sensors the frames of sensors 0..7 repeat (the same bytes are still
  uploaded). bytes_per_cycle counts the S*K frames up and S fused images down;
  bandwidth_fraction relates it to a buffer copy measured at start.
  Also at start of a run with Vulkan cells, probe kernels measure what any
  kernel pays on the device: ns per float copied through device addresses (plans
  beyond maxStorageBufferRange), through descriptor-bound buffers (every other
  plan) and as vec4; a shared-memory exchange; the multiply-add rate; one small
  dispatch. Each probe's output is checked.
  The peer (bench/peers/pipelines.py with /usr/bin/python3, else python3, needing
  numpy, pywt and cv2) times its own loop (>= 5 runs) on sensor 0's frames in
  float32; for S > 1 its time is S times that (Python fuses sensors in turn).
  The C++ peer (vkfuse-bench-peer-opencv, built where CMake finds OpenCV)
  does the same with OpenCV's C++ API on 2 threads, reusing its buffers.
  floor_ms prices the ideal pipeline of the cell's method and shape
  (bench/floor_model.cpp: its accesses at half a bound vec4 copy each, its
  flops at the multiply-add rate, its dispatches) at these probed costs.

Exit status: 0 done, 1 a run-time failure, 2 bad command line (one-line message).
)",
                                   ", ");
}

}  // namespace vkfuse::bench

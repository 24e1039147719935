// One cell of the benchmark matrix (what is run, on what, at what size) and
// what measuring it gave.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "axes.hpp"
#include "timing.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse::bench {

// One cell of the benchmark matrix: what is run, on what, at what size.

struct Cell {
    MethodVariant method;
    int levels = 0;  // pyramid levels; 0 for the pointwise methods
    Backend backend = Backend::Vulkan;
    Precision precision = Precision::Fp32;
    Size size;
    int frames = 3;   // K
    int sensors = 1;  // S
    std::string skip;  // non-empty: why this cell is not measured

    FusionSpec fusion() const;
    // Cells that differ only in backend share inputs, reference and peer.
    bool same_workload(const Cell& other) const;
    // What the numbers are held in: "fp64" (the CPU reference), "fp32", "fp16".
    std::string precision_name() const;
    // "wavelet/bior4.4 L3 QVGA K3 S1 vulkan", "... vulkan fp16"
    std::string describe() const;
};

// What one cell measured, as the table, the JSON and the plot report it.

struct StageTime {
    std::string name;
    double median_ms = 0;  // over the timed runs
};

// A peer pipeline (Python or OpenCV C++) run on sensor 0's frames of a workload.
struct PeerResult {
    std::string name;      // "pywt 1.1.1 wavedec2/waverec2 + numpy 1.24.2", "opencv-c++ 4.6.0 pyrDown/pyrUp"
    std::string failure;   // non-empty: the peer did not produce a result
    Timing per_sensor;     // the script's own loop, one sensor's cycle
    FusedError error;      // its fused image against the reference
    MetricError metric_error;
};

struct CellResult {
    Cell cell;
    std::string device;   // "llvmpipe (...)", or the CPU reference's description
    std::string driver;   // Vulkan cells: "llvmpipe Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)"
    std::string failure;  // the cell was meant to run but could not (device error)
    Timing timing;
    double plan_ms = 0;   // Plan construction (pipelines, buffers, recording)
    FusedError error;
    MetricError metric_error;
    // The metrics against the reference metrics of this backend's own fused
    // image: the reductions' error alone, without the fusion's (a max-abs
    // near-tie changes the image, and with it the metrics, legitimately).
    MetricError metric_error_own_image;
    int checked_sensors = 0;  // sensors compared with the reference
    double load_average = 0;  // host 1-minute load average when the cell started
    std::vector<StageTime> stages;          // with --profile, Vulkan only
    std::optional<double> bytes_per_cycle;  // uploads + readback, Vulkan only
    std::optional<double> copy_bandwidth;   // bytes/s of a device buffer copy, this run
    std::optional<double> kernel_copy_ns;   // ns per float a kernel copies via device addresses, this run
    std::optional<double> cycle_fixed_ms;   // an empty cycle's median on this device (time_empty_cycle), Vulkan only
    std::optional<double> floor_ms;         // the ideal pipeline on this device (floor_model.hpp), Vulkan only
    std::optional<PeerResult> peer;      // the Python pipeline of the method
    std::optional<PeerResult> cpp_peer;  // the OpenCV C++ pipeline (Laplacian, Brovey, channel-sum cells)

    bool measured() const { return cell.skip.empty() && failure.empty(); }
    double cycles_per_second() const { return timing.median_ms > 0 ? 1000.0 / timing.median_ms : 0; }
    // Sensor-cycles per second: every sensor's frames fused and scored once.
    double throughput() const { return cell.sensors * cycles_per_second(); }
    // Fused megapixels per second.
    double mpixels_per_second() const { return throughput() * cell.size.pixels() * 1e-6; }
    std::optional<double> bandwidth_fraction() const;
    // The peer's time for this cell's S sensors (it runs one; Python fuses sensors one after another).
    std::optional<double> peer_cell_ms() const;
    std::optional<double> peer_speedup() const;  // peer_cell_ms / median_ms
    std::optional<double> floor_fraction() const;  // floor_ms / median_ms
    std::optional<double> cpp_peer_cell_ms() const;
    std::optional<double> cpp_peer_speedup() const;  // cpp_peer_cell_ms / median_ms
};

}  // namespace vkfuse::bench

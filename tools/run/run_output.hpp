// run_output.hpp - what `vkfuse run --out DIR` writes:
//   DIR/metrics.jsonl                       one JSON object per sensor per cycle
//   DIR/fused/<serial>/<cycle>.png          every fused frame (8-bit, clamped); a frame
//                                           bit for bit the sensor's last one written is
//                                           another name for that file, not a new encoding
//   DIR/side_by_side/<object>_<serial>.png  the last static frame | the last fused frame, under a
//                                           caption: the static setting, the fused sequence and
//                                           method, the metrics' gains over the static frame
//   DIR/summary.json                        the summary `vkfuse run` prints
// DIR is a StagedDirectory's fresh staging directory: these files are new,
// and appear under the user's --out name only when the run succeeds.
#pragma once
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "run/image_write_queue.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/rig/rig.hpp"
#include "vkfuse/sensor/illumination.hpp"

namespace vkfuse::cli {

// One metrics line (no wall-clock values: a replay reproduces it exactly).
// With skipping on it also carries the cycle's largest tile change score;
// image_from_cycle, when given, names the earlier cycle whose fused PNG holds
// this cycle's image ("image_from_cycle").
std::string metrics_line(const CycleResult& cycle, const SensorCycle& sensor, const std::string& object,
                         bool skipping, std::optional<std::uint64_t> image_from_cycle = std::nullopt);

// The slot of sequence lit by every LED at full level (the sensor's usual,
// static illumination), else slot 0.
std::size_t static_slot(const IlluminationSequence& sequence, const LedLayout& leds);

// Whether name is a top-level entry RunOutput writes (what --replace may replace).
bool is_run_output_entry(const std::string& name);

// What the side-by-side pictures' captions name.
struct RunOutputLabels {
    IlluminationSequence sequence;
    std::size_t static_slot = 0;  // static_slot(sequence, leds)
    std::string method;           // method_label()
    MetricSet metrics = MetricSet::all();
};

class RunOutput {
public:
    // directory must exist and be empty (a staging directory). object and the
    // serials become file names and must be plain components (checked:
    // Error(Format) otherwise, whatever a replayed dataset says).
    RunOutput(std::string directory, std::string object, RunOutputLabels labels, bool skipping);
    ~RunOutput();
    RunOutput(const RunOutput&) = delete;
    RunOutput& operator=(const RunOutput&) = delete;

    // The cycle's metric lines now; its fused PNGs on a writer thread (an
    // error there fails a later write() or finish()).
    void write(const CycleResult& cycle);
    // A sensor's background frames of one setting (RigConfig::on_background;
    // sensors' threads may call it at once): the static setting's mean is
    // what the static frame's difference with background is measured against.
    void add_background(const std::string& serial, const Illumination& setting, const std::vector<Frame>& frames);
    // Side-by-side pictures and the summary; closes metrics.jsonl.
    void finish(const std::string& summary_json);

private:
    // A sensor's last whole cycle, for its side-by-side picture.
    struct Last {
        Frame still;  // the static setting's frame
        std::shared_ptr<const Image> fused;
        Metrics metrics;
        std::uint64_t cycle = 0;
    };
    // A sensor's last fused PNG encoded: later cycles with the same bits name it.
    struct Written {
        std::shared_ptr<const Image> image;
        std::string path;
        std::uint64_t cycle = 0;
    };
    Image captioned_side_by_side(const std::string& serial, const Last& last) const;

    std::string directory_, object_;
    RunOutputLabels labels_;
    bool skipping_;
    int metrics_fd_ = -1;
    std::vector<std::pair<std::string, Last>> last_;  // by serial, in sensor order
    std::map<std::string, Written> written_;           // by serial
    std::mutex backgrounds_mutex_;
    std::map<std::string, ImageD> static_backgrounds_;  // by serial
    ImageWriteQueue fused_pngs_;  // last: stopped before anything it writes about goes
};

}  // namespace vkfuse::cli

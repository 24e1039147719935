// vkfuse/sensor/dataset.hpp - recorded sensor frames on disk, in either of two
// forms (README, "Datasets"): a folder of lossless 8-bit PNGs plus one JSON
// manifest, or one MCAP file (a path ending in .mcap) in ROS 2's types, which
// ros2 bag, Foxglove and the MCAP tools open. Written by `vkfuse sim`,
// `vkfuse run --record` and `vkfuse convert`, replayed as a Sensor by
// `vkfuse run --replay`; both forms hold the same facts.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "vkfuse/core/fusion.hpp"
#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/sensor/switching.hpp"
#include "vkfuse/sensor/sensor.hpp"

namespace vkfuse {

// One recorded frame.
struct DatasetFrame {
    std::string file;           // a folder's PNG, relative to the dataset directory
    // An MCAP recording's frame: where its message lies (its chunk's file
    // offset, and its record's offset in the chunk).
    std::uint64_t chunk = 0, record = 0;
    std::uint64_t index = 0;    // the sensor's frame counter
    double timestamp = 0;       // start of exposure, sensor clock (seconds)
    Illumination illumination;  // the setting that lit the whole frame
    std::int64_t cycle = -1;    // vkfuse run: the fused cycle it went into; -1 otherwise
};

// Frames of one object (or of nothing: the background), in capture order.
struct DatasetTake {
    std::string object;  // "nothing" for a background take
    bool background = false;
    std::vector<DatasetFrame> frames;
};

// A cycle of a recorded `vkfuse run` in which this sensor delivered nothing,
// as the run reported it, so a replay reports the same.
struct DatasetMiss {
    std::int64_t cycle = 0;
    std::string status;  // "timeout" or "failed"
    std::string error;
};

struct DatasetSensorRecord {
    SensorInfo info;
    std::vector<DatasetTake> takes;  // background takes first
    std::vector<DatasetMiss> missed;  // in cycle order
};

// How a recorded `vkfuse run` fused its frames, so a replay can do the same.
struct DatasetRun {
    IlluminationSequence sequence;
    FusionSpec fusion;
    int background_frames = 0;  // per setting, in each sensor's background take
    // Sliding: each recorded cycle is one window, its K frames recorded whole
    // (a frame is in up to K windows; a folder writes its PNG once).
    FusionWindow window = FusionWindow::Cycle;
};

// An MCAP recording kept open while its dataset is in use.
struct DatasetStorage;

struct Dataset {
    std::string directory;  // the folder, or the .mcap file
    std::string source;  // "vkfuse sim", "vkfuse run", ...
    std::vector<DatasetSensorRecord> sensors;
    std::optional<DatasetRun> run;
    std::shared_ptr<DatasetStorage> storage;  // an MCAP recording's; nullptr for a folder
    // A recording cut short (a crash, a full disk): where reading stopped and
    // why, in one line; "" when it is whole. Its dataset holds the whole
    // cycles before that point.
    std::string incomplete;

    // Throws Error(InvalidArgument) "<directory>: no sensor <serial> (has ...)".
    const DatasetSensorRecord& sensor(const std::string& serial) const;
    // Objects with frames (background takes excluded), in recording order.
    std::vector<std::string> objects() const;
    // Background frames per setting a replay of sequence takes before the
    // object's frames: the recorded run's, or for a dataset that recorded no
    // run (`vkfuse sim`) as many as every sensor holds for every setting.
    int background_frames(const IlluminationSequence& sequence) const;
};

// Reads and checks DIR/manifest.json, or a recording's .mcap file (frames are
// loaded when played). Throws Error(Io) when it is missing, Error(Format)
// "DIR/manifest.json: <where>: <problem>" or "FILE.mcap: byte N: <record>:
// <problem>" when it is malformed.
Dataset read_dataset(const std::string& path);

// Whether path names the MCAP form (it ends in ".mcap").
bool is_mcap_path(const std::string& path);

// Loads one recorded frame as the sensor delivered it (PNG -> 8-bit RGB).
// Throws Error naming the file when it is missing, corrupt or of another shape.
Frame load_frame(const Dataset& dataset, const DatasetSensorRecord& sensor, const DatasetFrame& frame);

// How an MCAP recording is written.
struct DatasetWriterOptions {
    std::string compression = "zstd";  // of its chunks: zstd, lz4 or none
};

// Writes a dataset. Thread-safe: capture threads of several sensors may add
// frames at once (each PNG is written outside the lock). A folder's manifest
// is written by finish(), atomically, and may be rewritten after more frames;
// an MCAP file is streamed (sensors and run first, then frames as they come)
// and closed by finish(), its summary and index last.
class DatasetWriter {
public:
    // A path ending in .mcap: creates that file, refusing one that exists.
    // Otherwise creates the directory (parents too), refusing one that exists
    // and is not empty.
    DatasetWriter(std::string path, std::string source, DatasetWriterOptions options = {});
    ~DatasetWriter();

    // Registers a sensor; returns its index for add_frame.
    int add_sensor(const SensorInfo& info);
    void set_run(const DatasetRun& run);
    // Writes frame as DIR/<serial>/<take>/<r-g-b>/<nnnnnn>.png, where take is
    // "background" or the object, and lists it in the manifest; or as a
    // message on the recording's /vkfuse/<token>/frame. An MCAP recording
    // takes every sensor and the run before its first frame.
    void add_frame(int sensor, const std::string& object, bool background, const Frame& frame,
                   const Illumination& lit_by, std::int64_t cycle = -1);
    // A cycle in which sensor delivered nothing (status "timeout" or "failed").
    void add_miss(int sensor, const DatasetMiss& miss);
    void finish();

    const std::string& directory() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

// Plays one recorded sensor: its background takes, then the takes of one
// object. set_illumination(s) selects the frames recorded under s (in
// recording order, backgrounds first); grab() returns the next of them with
// its recorded index, timestamp, illumination and cycle, without waiting. So a
// rig that requests the same settings in the same order as the recorded run
// gets the very same frames, each in the cycle it was recorded in. Throws Error naming the serial when a setting has no
// frames or its frames are used up.
class DatasetSensor : public Sensor {
public:
    DatasetSensor(std::shared_ptr<const Dataset> dataset, const std::string& serial, const std::string& object);
    ~DatasetSensor() override;

    SensorInfo info() const override;
    void set_illumination(const Illumination& setting) override;
    Frame grab() override;

    // Frames recorded under setting (background takes included).
    std::size_t frames_lit_by(const Illumination& setting, bool background) const;
    // How many cycles of sequence a replay plays: for frames recorded by
    // `vkfuse run` (with cycle numbers) the last recorded cycle + 1, cycles
    // the sensor missed included; otherwise the full cycles the takes hold.
    std::size_t cycles_available(const IlluminationSequence& sequence) const;
    // Decodes every frame it will play now, so grab() only copies: a replay
    // that keeps the sensors' own pace never waits on a decoder. Holds
    // frames() * height * width * 3 bytes.
    void preload();
    // Frames it plays (background takes and the object's), for a preload's memory check.
    std::size_t frames() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

// What record_dataset captures and how it reports progress.
struct RecordOptions {
    std::vector<std::string> objects;  // pressed one after another
    std::vector<Illumination> grid;    // every object is captured under each
    int frames = 1;                    // per object x setting
    int background_frames = 1;         // per setting, with nothing pressed
    // Puts an object on the sensor ("nothing" for the background); a simulated
    // DIGIT calls set_object, a real rig asks its operator or robot.
    std::function<void(const std::string& object)> place_object;
    std::function<void(std::size_t done, std::size_t total)> progress;  // frames
};

// Records from any sensor: measures its switch timing once (scene still, so
// with nothing pressed), then the background under every setting, then each
// object under every setting, taking only frames lit entirely by the setting.
void record_dataset(Sensor& sensor, std::shared_ptr<Clock> clock, DatasetWriter& writer, const RecordOptions& options);

// "15,15,15" -> "15-15-15": how a setting names a directory.
std::string illumination_dir_name(const Illumination& setting);

}  // namespace vkfuse

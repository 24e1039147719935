// sensor/dataset_mcap.hpp - a dataset as one MCAP file
// (sensor/recording_messages.hpp says what it holds): written as a stream,
// read back through io::mcap::Reader, a truncated file up to its last whole
// cycle.
#pragma once
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/mcap_reader.hpp"
#include "io/mcap_writer.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse {

struct DatasetStorage {
    io::mcap::Reader reader;
    explicit DatasetStorage(const std::string& path) : reader(path) {}
};

namespace sensor {

// The writing side of DatasetWriter for a .mcap path. Not thread-safe: the
// writer calls it under its lock.
class McapDatasetWriter {
public:
    McapDatasetWriter(const std::string& path, const std::string& compression);
    ~McapDatasetWriter();
    McapDatasetWriter(const McapDatasetWriter&) = delete;
    McapDatasetWriter& operator=(const McapDatasetWriter&) = delete;

    // The first frame or miss writes what dataset says of its sensors and run.
    void add_frame(const Dataset& dataset, int sensor, const std::string& object, bool background, const Frame& frame,
                   const Illumination& lit_by, std::int64_t cycle);
    void add_miss(const Dataset& dataset, int sensor, const DatasetMiss& miss);
    // Whether the sensors and run are written (no more may be added).
    bool started() const { return started_; }
    // The summary, then the file flushed to disk and closed.
    void finish(const Dataset& dataset);

private:
    void start(const Dataset& dataset);
    // /vkfuse/rig's one message, before the first frame or miss.
    void describe(const Dataset& dataset, std::uint64_t time_ns);

    std::string path_;
    std::FILE* file_ = nullptr;
    std::unique_ptr<io::mcap::Writer> writer_;
    std::size_t sensors_ = 0;  // those described when it started
    std::vector<std::uint16_t> frame_channels_, metrics_channels_;
    std::uint16_t rig_channel_ = 0;
    std::vector<std::uint32_t> frame_sequences_, miss_sequences_;
    std::vector<std::uint64_t> last_time_;  // per sensor: a miss is dated by the frame before it
    bool started_ = false, described_ = false, finished_ = false;
};

Dataset read_mcap_dataset(const std::string& path);
Frame load_mcap_frame(const Dataset& dataset, const DatasetSensorRecord& sensor, const DatasetFrame& frame);

}  // namespace sensor
}  // namespace vkfuse

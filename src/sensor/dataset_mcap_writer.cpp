// A dataset streamed into an MCAP file (dataset_mcap.hpp).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/json_value.hpp"
#include "io/mcap_records.hpp"
#include "sensor/dataset_manifest.hpp"
#include "sensor/dataset_mcap.hpp"
#include "sensor/recording_messages.hpp"
#include "sensor/ros2_schema.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/version.hpp"

namespace vkfuse::sensor {
McapDatasetWriter::McapDatasetWriter(const std::string& path, const std::string& compression) : path_(path) {
    const auto c = io::mcap::parse_compression_option(compression);
    if (!c) throw Error(ErrorKind::InvalidArgument, path + ": compression " + compression + " (expected zstd, lz4 or none)");
    // O_EXCL: never onto a file (or a planted link) that is already there.
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
        if (errno == EEXIST) throw Error(ErrorKind::Io, path + ": exists (a recording needs a new file)");
        throw Error(ErrorKind::Io, path + ": cannot create: " + std::strerror(errno));
    }
    file_ = ::fdopen(fd, "wb");
    if (!file_) {
        ::close(fd);
        throw Error(ErrorKind::Io, path + ": cannot open: " + std::strerror(errno));
    }
    io::mcap::WriterOptions options;
    options.profile = "ros2";
    options.library = "vkfuse " + std::string(kVersion);
    options.compression = *c;
    writer_ = std::make_unique<io::mcap::Writer>(file_, path, options);
}

McapDatasetWriter::~McapDatasetWriter() {
    if (file_) std::fclose(file_);
}

void McapDatasetWriter::start(const Dataset& dataset) {
    if (started_) return;
    started_ = true;
    // The manifest without frames: the sensors, the source, the run.
    Dataset described = dataset;
    for (DatasetSensorRecord& s : described.sensors) {
        s.takes.clear();
        s.missed.clear();
    }
    writer_->add_metadata(std::string(recording::kMetadataName),
                          {{std::string(recording::kManifestKey), json::write(manifest_json(described))}});
    const std::string frame_schema = ros2msg_schema(recording::kFrameType);
    const std::string metrics_schema = ros2msg_schema(recording::kMetricsType);
    const auto frames =
        writer_->add_schema(std::string(recording::kFrameType), "ros2msg", io::mcap::bytes_of(frame_schema));
    const auto metrics =
        writer_->add_schema(std::string(recording::kMetricsType), "ros2msg", io::mcap::bytes_of(metrics_schema));
    const auto rig = writer_->add_schema(std::string(recording::kRigType), "ros2msg",
                                         io::mcap::bytes_of(ros2msg_schema(recording::kRigType)));
    // rosbag2 reads each channel's QoS from this key; empty: the defaults.
    const std::map<std::string, std::string> qos{{"offered_qos_profiles", ""}};
    for (const DatasetSensorRecord& s : dataset.sensors) {
        frame_channels_.push_back(writer_->add_channel(frames, recording::frame_topic(s.info.serial), "cdr", qos));
        metrics_channels_.push_back(writer_->add_channel(metrics, recording::metrics_topic(s.info.serial), "cdr", qos));
    }
    rig_channel_ = writer_->add_channel(rig, std::string(recording::kRigTopic), "cdr", qos);
    sensors_ = dataset.sensors.size();
    frame_sequences_.assign(sensors_, 0);
    miss_sequences_.assign(sensors_, 0);
    last_time_.assign(sensors_, 0);
}

void McapDatasetWriter::describe(const Dataset& dataset, std::uint64_t time_ns) {
    // Dated as the first message after it, since players (ros2 bag play)
    // start at the earliest message: one at 0 would hold up the frames.
    if (described_) return;
    described_ = true;
    writer_->write(rig_channel_, 0, time_ns, time_ns, io::mcap::bytes_of(recording::encode_rig(dataset, time_ns)));
}

void McapDatasetWriter::add_frame(const Dataset& dataset, int sensor, const std::string& object, bool background,
                                  const Frame& frame, const Illumination& lit_by, std::int64_t cycle) {
    start(dataset);
    const std::size_t i = std::size_t(sensor);
    if (i >= sensors_) throw Error(ErrorKind::InvalidArgument, path_ + ": sensor #" + std::to_string(sensor) + " added after the first frame");
    const std::string& serial = dataset.sensors[i].info.serial;
    const std::uint64_t t = recording::frame_time_ns(frame.timestamp);
    last_time_[i] = std::max(last_time_[i], t);
    describe(dataset, t);
    writer_->write(frame_channels_[i], frame_sequences_[i]++, t, t,
                   io::mcap::bytes_of(recording::encode_frame(serial, frame, lit_by, object, background, cycle)));
}

void McapDatasetWriter::add_miss(const Dataset& dataset, int sensor, const DatasetMiss& miss) {
    start(dataset);
    const std::size_t i = std::size_t(sensor);
    if (i >= sensors_) throw Error(ErrorKind::InvalidArgument, path_ + ": sensor #" + std::to_string(sensor) + " added after the first frame");
    describe(dataset, last_time_[i]);
    writer_->write(metrics_channels_[i], miss_sequences_[i]++, last_time_[i], last_time_[i],
                   io::mcap::bytes_of(recording::encode_miss(dataset.sensors[i].info.serial, miss, last_time_[i])));
}

void McapDatasetWriter::finish(const Dataset& dataset) {
    if (finished_) return;
    start(dataset);
    describe(dataset, 0);
    writer_->finish();
    finished_ = true;
    if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0)
        throw Error(ErrorKind::Io, path_ + ": cannot write: " + std::strerror(errno));
    std::FILE* f = file_;
    file_ = nullptr;
    if (std::fclose(f) != 0) throw Error(ErrorKind::Io, path_ + ": cannot write: " + std::strerror(errno));
}

}  // namespace vkfuse::sensor

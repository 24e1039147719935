// DatasetWriter: a folder's PNG frames as they come and its manifest when
// asked, or an MCAP recording's messages (dataset_mcap_writer.cpp).
#include <cstdio>
#include <filesystem>
#include <map>
#include <system_error>

#include "io/atomic_write.hpp"
#include "io/path_component.hpp"
#include "sensor/dataset_manifest.hpp"
#include "sensor/dataset_mcap.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse {
namespace {

namespace fs = std::filesystem;

void prepare_directory(const std::string& directory) {
    std::error_code ec;
    if (fs::exists(directory, ec) && !fs::is_empty(directory, ec))
        throw Error(ErrorKind::Io, directory + ": exists and is not empty (a dataset needs a new directory)");
    fs::create_directories(directory, ec);
    if (ec) throw Error(ErrorKind::Io, directory + ": cannot create: " + ec.message());
}


Image to_image(const Frame& f) {
    Image img(f.height, f.width, 3);
    for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = float(f.pixels[i]) / 255.0f;
    return img;
}

// The frame a folder wrote last under one take and setting of a sensor: a
// sliding window's frames are recorded once per window they are in, and the
// same frame again is listed with the PNG it already has.
struct WrittenFrame {
    std::uint64_t index = 0;
    double timestamp = 0;
    std::vector<std::uint8_t> pixels;
    std::string file;

    bool same(const Frame& f) const { return f.index == index && f.timestamp == timestamp && f.pixels == pixels; }
};

}  // namespace

struct DatasetWriter::Impl {
    std::mutex mutex;
    Dataset dataset;  // an MCAP recording's without its frames
    std::vector<std::size_t> file_counters;  // per sensor, a folder's
    std::vector<std::map<std::string, WrittenFrame>> written;  // per sensor, a folder's: by take and setting
    std::unique_ptr<sensor::McapDatasetWriter> mcap;

    // An MCAP recording describes its sensors and run before its first frame.
    void check_not_started(const char* what) const {
        if (mcap && mcap->started())
            throw Error(ErrorKind::InvalidArgument, dataset.directory + ": " + what +
                                                        " after the first frame (an MCAP recording describes them first)");
    }
    void check_sensor(int sensor) const {
        if (sensor < 0 || std::size_t(sensor) >= dataset.sensors.size())
            throw Error(ErrorKind::InvalidArgument, dataset.directory + ": no sensor #" + std::to_string(sensor));
    }
};

DatasetWriter::DatasetWriter(std::string path, std::string source, DatasetWriterOptions options)
    : impl_(std::make_unique<Impl>()) {
    if (is_mcap_path(path))
        impl_->mcap = std::make_unique<sensor::McapDatasetWriter>(path, options.compression);
    else
        prepare_directory(path);
    impl_->dataset.directory = std::move(path);
    impl_->dataset.source = std::move(source);
}

DatasetWriter::~DatasetWriter() = default;

const std::string& DatasetWriter::directory() const { return impl_->dataset.directory; }

int DatasetWriter::add_sensor(const SensorInfo& info) {
    io::check_plain_component(info.serial, "serial");
    std::lock_guard lock(impl_->mutex);
    impl_->check_not_started("a sensor added");
    for (const DatasetSensorRecord& s : impl_->dataset.sensors)
        if (s.info.serial == info.serial)
            throw Error(ErrorKind::InvalidArgument, impl_->dataset.directory + ": sensor " + info.serial + " added twice");
    impl_->dataset.sensors.push_back({info, {}, {}});
    impl_->file_counters.push_back(0);
    impl_->written.emplace_back();
    return int(impl_->dataset.sensors.size()) - 1;
}

void DatasetWriter::set_run(const DatasetRun& run) {
    std::lock_guard lock(impl_->mutex);
    impl_->check_not_started("the run set");
    impl_->dataset.run = run;
}

void DatasetWriter::add_frame(int sensor, const std::string& object, bool background, const Frame& frame,
                              const Illumination& lit_by, std::int64_t cycle) {
    const std::string take = background ? std::string("background") : object;
    io::check_plain_component(take, "object");
    Impl& im = *impl_;
    std::string relative;
    const std::string written_key = take + "/" + illumination_dir_name(lit_by);
    DatasetFrame f;
    f.index = frame.index;
    f.timestamp = frame.timestamp;
    f.illumination = lit_by;
    f.cycle = cycle;
    {
        std::lock_guard lock(im.mutex);
        im.check_sensor(sensor);
        if (im.mcap) {
            im.mcap->add_frame(im.dataset, sensor, object, background, frame, lit_by, cycle);
            return;
        }
        auto& written = im.written[std::size_t(sensor)];
        if (auto it = written.find(written_key); it != written.end() && it->second.same(frame)) {
            f.file = it->second.file;
            sensor::take_of(im.dataset.sensors[std::size_t(sensor)], object, background).frames.push_back(std::move(f));
            return;
        }
        char number[32];
        std::snprintf(number, sizeof number, "%06zu.png", im.file_counters[std::size_t(sensor)]++);
        relative = (fs::path(im.dataset.sensors[std::size_t(sensor)].info.serial) / take /
                    illumination_dir_name(lit_by) / number)
                       .string();
    }
    // The PNG is written outside the lock: other sensors' threads go on meanwhile.
    const fs::path path = fs::path(im.dataset.directory) / relative;
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(ErrorKind::Io, path.parent_path().string() + ": cannot create: " + ec.message());
    io::write_image(path.string(), to_image(frame));
    std::lock_guard lock(im.mutex);
    f.file = relative;
    im.written[std::size_t(sensor)][written_key] = WrittenFrame{frame.index, frame.timestamp, frame.pixels, relative};
    sensor::take_of(im.dataset.sensors[std::size_t(sensor)], object, background).frames.push_back(std::move(f));
}

void DatasetWriter::add_miss(int sensor, const DatasetMiss& miss) {
    if (miss.status != "timeout" && miss.status != "failed")
        throw Error(ErrorKind::InvalidArgument, impl_->dataset.directory + ": miss status \"" + miss.status +
                                                    "\" (expected timeout or failed)");
    std::lock_guard lock(impl_->mutex);
    impl_->check_sensor(sensor);
    if (impl_->mcap)
        impl_->mcap->add_miss(impl_->dataset, sensor, miss);
    else
        impl_->dataset.sensors[std::size_t(sensor)].missed.push_back(miss);
}

void DatasetWriter::finish() {
    std::string text;
    {
        std::lock_guard lock(impl_->mutex);
        if (impl_->mcap) {
            impl_->mcap->finish(impl_->dataset);
            return;
        }
        text = json::write(sensor::manifest_json(impl_->dataset));
    }
    const std::string path = (fs::path(impl_->dataset.directory) / sensor::kManifestName).string();
    io::write_atomically(path, [&](std::FILE* out) {
        if (std::fwrite(text.data(), 1, text.size(), out) != text.size())
            throw Error(ErrorKind::Io, path + ": write failed");
    });
}

}  // namespace vkfuse

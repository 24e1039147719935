// DatasetWriter: PNG frames as they come, the manifest when asked.
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "io/atomic_write.hpp"
#include "io/path_component.hpp"
#include "sensor/dataset_manifest.hpp"
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

DatasetTake& take_of(DatasetSensorRecord& s, const std::string& object, bool background) {
    for (DatasetTake& t : s.takes)
        if (t.object == object && t.background == background) return t;
    s.takes.push_back({object, background, {}});
    return s.takes.back();
}

}  // namespace

DatasetWriter::DatasetWriter(std::string directory, std::string source) {
    prepare_directory(directory);
    dataset_.directory = std::move(directory);
    dataset_.source = std::move(source);
}

int DatasetWriter::add_sensor(const SensorInfo& info) {
    io::check_plain_component(info.serial, "serial");
    std::lock_guard lock(mutex_);
    for (const DatasetSensorRecord& s : dataset_.sensors)
        if (s.info.serial == info.serial)
            throw Error(ErrorKind::InvalidArgument, dataset_.directory + ": sensor " + info.serial + " added twice");
    dataset_.sensors.push_back({info, {}, {}});
    file_counters_.push_back(0);
    return int(dataset_.sensors.size()) - 1;
}

void DatasetWriter::set_run(const DatasetRun& run) {
    std::lock_guard lock(mutex_);
    dataset_.run = run;
}

void DatasetWriter::add_frame(int sensor, const std::string& object, bool background, const Frame& frame,
                              const Illumination& lit_by, std::int64_t cycle) {
    const std::string take = background ? std::string("background") : object;
    io::check_plain_component(take, "object");
    std::string relative;
    {
        std::lock_guard lock(mutex_);
        if (sensor < 0 || std::size_t(sensor) >= dataset_.sensors.size())
            throw Error(ErrorKind::InvalidArgument, dataset_.directory + ": no sensor #" + std::to_string(sensor));
        char number[32];
        std::snprintf(number, sizeof number, "%06zu.png", file_counters_[std::size_t(sensor)]++);
        relative = (fs::path(dataset_.sensors[std::size_t(sensor)].info.serial) / take / illumination_dir_name(lit_by) /
                    number)
                       .string();
    }
    // The PNG is written outside the lock: other sensors' threads go on meanwhile.
    const fs::path path = fs::path(dataset_.directory) / relative;
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(ErrorKind::Io, path.parent_path().string() + ": cannot create: " + ec.message());
    io::write_image(path.string(), to_image(frame));
    std::lock_guard lock(mutex_);
    take_of(dataset_.sensors[std::size_t(sensor)], object, background)
        .frames.push_back({relative, frame.index, frame.timestamp, lit_by, cycle});
}

void DatasetWriter::add_miss(int sensor, const DatasetMiss& miss) {
    if (miss.status != "timeout" && miss.status != "failed")
        throw Error(ErrorKind::InvalidArgument, dataset_.directory + ": miss status \"" + miss.status +
                                                    "\" (expected timeout or failed)");
    std::lock_guard lock(mutex_);
    if (sensor < 0 || std::size_t(sensor) >= dataset_.sensors.size())
        throw Error(ErrorKind::InvalidArgument, dataset_.directory + ": no sensor #" + std::to_string(sensor));
    dataset_.sensors[std::size_t(sensor)].missed.push_back(miss);
}

void DatasetWriter::finish() {
    std::string text;
    {
        std::lock_guard lock(mutex_);
        text = json::write(sensor::manifest_json(dataset_));
    }
    const std::string path = (fs::path(dataset_.directory) / sensor::kManifestName).string();
    io::write_atomically(path, [&](std::FILE* out) {
        if (std::fwrite(text.data(), 1, text.size(), out) != text.size())
            throw Error(ErrorKind::Io, path + ": write failed");
    });
}

}  // namespace vkfuse

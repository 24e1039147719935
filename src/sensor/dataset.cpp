// Reading a dataset: the manifest, and frames as the sensor delivered them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "io/file_bytes.hpp"
#include "io/path_component.hpp"
#include "io/png.hpp"
#include "sensor/dataset_manifest.hpp"
#include "sensor/dataset_mcap.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse {

const DatasetSensorRecord& Dataset::sensor(const std::string& serial) const {
    std::string known;
    for (const DatasetSensorRecord& s : sensors) {
        if (s.info.serial == serial) return s;
        known += (known.empty() ? "" : ", ") + s.info.serial;
    }
    throw Error(ErrorKind::InvalidArgument, directory + ": no sensor " + serial + " (has " + known + ")");
}

std::vector<std::string> Dataset::objects() const {
    std::vector<std::string> out;
    for (const DatasetSensorRecord& s : sensors)
        for (const DatasetTake& t : s.takes)
            if (!t.background && std::find(out.begin(), out.end(), t.object) == out.end()) out.push_back(t.object);
    return out;
}

int Dataset::background_frames(const IlluminationSequence& sequence) const {
    if (run) return run->background_frames;
    std::size_t fewest = std::numeric_limits<std::size_t>::max();
    for (const DatasetSensorRecord& s : sensors)
        for (const Illumination& setting : sequence) {
            std::size_t n = 0;
            for (const DatasetTake& t : s.takes)
                if (t.background)
                    n += std::size_t(std::count_if(t.frames.begin(), t.frames.end(),
                                                   [&](const DatasetFrame& f) { return f.illumination == setting; }));
            fewest = std::min(fewest, n);
        }
    return sensors.empty() || sequence.empty() ? 0 : int(fewest);
}

bool is_mcap_path(const std::string& path) {
    return path.size() > 5 && path.compare(path.size() - 5, 5, ".mcap") == 0;
}

Dataset read_dataset(const std::string& directory) {
    if (is_mcap_path(directory)) return sensor::read_mcap_dataset(directory);
    const std::string file = io::resolve_inside(directory, sensor::kManifestName);
    // A manifest lists frames at ~150 bytes each: 256 MiB is over a million
    // frames, and keeps a hostile one from choosing how much memory we take.
    constexpr std::uint64_t kMaxManifestBytes = std::uint64_t(256) << 20;
    const std::vector<unsigned char> bytes = io::read_file_bytes(file, kMaxManifestBytes);
    const json::Value manifest =
        json::parse(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file);
    Dataset d = sensor::dataset_from_json(manifest, file, directory);
    sensor::check_unique_serials(d, file);
    return d;
}

Frame load_frame(const Dataset& dataset, const DatasetSensorRecord& sensor, const DatasetFrame& frame) {
    if (dataset.storage) return sensor::load_mcap_frame(dataset, sensor, frame);
    const std::string path = io::resolve_inside(dataset.directory, frame.file);
    const Image image = io::read_image(path);
    const SensorInfo& info = sensor.info;
    if (image.height != info.height || image.width != info.width || image.channels != 3)
        throw Error(ErrorKind::Shape, path + ": shape " + std::to_string(image.height) + "x" +
                                          std::to_string(image.width) + "x" + std::to_string(image.channels) +
                                          " differs from sensor " + info.serial + "'s " + std::to_string(info.height) +
                                          "x" + std::to_string(info.width) + "x3");
    Frame f;
    f.index = frame.index;
    f.timestamp = frame.timestamp;
    f.height = image.height;
    f.width = image.width;
    f.illumination = frame.illumination;
    f.recorded_cycle = frame.cycle;
    // v / 255 read back from an 8-bit PNG: rounding restores the byte exactly.
    f.pixels = io::to_8bit(image);
    return f;
}

std::string illumination_dir_name(const Illumination& setting) {
    std::string name = setting.to_string();
    std::replace(name.begin(), name.end(), ',', '-');
    return name;
}

}  // namespace vkfuse

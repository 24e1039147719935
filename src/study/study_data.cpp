#include "study/study_data.hpp"

#include <algorithm>
#include <cstdint>

#include "vkfuse/core/error.hpp"

namespace vkfuse::study {
namespace {

[[noreturn]] void fail(const Dataset& dataset, const std::string& problem) {
    throw Error(ErrorKind::InvalidArgument, dataset.directory + ": " + problem);
}

std::size_t index_of(const std::vector<Illumination>& settings, const Illumination& s) {
    return std::size_t(std::find(settings.begin(), settings.end(), s) - settings.begin());
}

}  // namespace

void check_study_size(std::size_t settings, const std::vector<std::string>& objects, int height, int width,
                      const std::string& subject) {
    const auto fail_with = [&](const std::string& problem) {
        throw Error(ErrorKind::InvalidArgument, subject + ": " + problem);
    };
    if (settings < 2) fail_with(std::to_string(settings) + " setting" + (settings == 1 ? "" : "s") +
                                "; a study fuses two or more");
    if (settings > kMaxSettings)
        fail_with(std::to_string(settings) + " settings, more than a study takes (" + std::to_string(kMaxSettings) + ")");
    if (objects.size() > kMaxObjects)
        fail_with(std::to_string(objects.size()) + " objects, more than a study takes (" + std::to_string(kMaxObjects) +
                  ")");
    for (auto it = objects.begin(); it != objects.end(); ++it)
        if (std::find(objects.begin(), it, *it) != it) fail_with("object \"" + *it + "\" named twice");
    const std::size_t frame_bytes = std::size_t(std::max(height, 0)) * std::size_t(std::max(width, 0)) * 3;
    if (objects.size() * settings * frame_bytes > kMaxFrameBytes)
        fail_with(std::to_string(objects.size()) + " objects x " + std::to_string(settings) + " settings of " +
                  std::to_string(width) + "x" + std::to_string(height) +
                  " frames are more than a study holds in memory (" + std::to_string(kMaxFrameBytes >> 30) +
                  " GiB); study fewer objects");
}

StudyData load_study_data(const Dataset& dataset, const std::string& serial, const std::vector<std::string>& objects) {
    if (dataset.sensors.empty()) fail(dataset, "no sensor recorded");
    const DatasetSensorRecord& sensor = serial.empty() ? dataset.sensors.front() : dataset.sensor(serial);
    StudyData d;
    d.height = sensor.info.height;
    d.width = sensor.info.width;

    // Settings in the order their backgrounds were recorded, each with the
    // frames that will be averaged into its background.
    std::vector<std::vector<const DatasetFrame*>> background_frames;
    for (const DatasetTake& take : sensor.takes) {
        if (!take.background) continue;
        for (const DatasetFrame& f : take.frames) {
            const std::size_t i = index_of(d.settings, f.illumination);
            if (i == d.settings.size()) {
                if (d.settings.size() == kMaxSettings)
                    fail(dataset, "sensor " + sensor.info.serial + " has more than " + std::to_string(kMaxSettings) +
                                      " settings, more than a study takes");
                d.settings.push_back(f.illumination);
                background_frames.emplace_back();
            }
            background_frames[i].push_back(&f);
        }
    }
    if (d.settings.empty()) fail(dataset, "sensor " + sensor.info.serial + " has no background frames");
    if (d.settings.size() < 2)
        fail(dataset, "sensor " + sensor.info.serial + " has one setting only; a study fuses two or more");
    const LedLayout& leds = sensor.info.leds;
    d.static_setting = std::size_t(std::find_if(d.settings.begin(), d.settings.end(),
                                                [&](const Illumination& s) { return s.is_full(leds); }) -
                                   d.settings.begin());
    if (d.static_setting == d.settings.size())
        fail(dataset, "no background under the static setting (every LED at " + std::to_string(leds.max_level) +
                          "), which every gain is measured against");

    // The objects this sensor pressed, in recording order.
    std::vector<std::string> known;
    for (const DatasetTake& take : sensor.takes)
        if (!take.background && std::find(known.begin(), known.end(), take.object) == known.end())
            known.push_back(take.object);
    d.objects = objects.empty() ? known : objects;
    if (d.objects.empty()) fail(dataset, "sensor " + sensor.info.serial + " has no object frames, only backgrounds");
    check_study_size(d.settings.size(), d.objects, d.height, d.width, dataset.directory);
    for (auto it = d.objects.begin(); it != d.objects.end(); ++it) {
        const std::string& object = *it;
        if (std::find(known.begin(), known.end(), object) == known.end())
            fail(dataset, "no object \"" + object + "\" for sensor " + sensor.info.serial);
        std::vector<const DatasetFrame*> first(d.settings.size(), nullptr);
        for (const DatasetTake& take : sensor.takes) {
            if (take.background || take.object != object) continue;
            for (const DatasetFrame& f : take.frames) {
                const std::size_t i = index_of(d.settings, f.illumination);
                if (i == d.settings.size())
                    fail(dataset, "object \"" + object + "\" has frames under " + f.illumination.to_string() +
                                      ", which has no background");
                if (!first[i]) first[i] = &f;
            }
        }
        std::vector<Frame> frames;
        for (std::size_t i = 0; i < d.settings.size(); ++i) {
            if (!first[i])
                fail(dataset, "object \"" + object + "\" has no frame under " + d.settings[i].to_string() +
                                  " (a study needs every object under every setting)");
            frames.push_back(load_frame(dataset, sensor, *first[i]));
        }
        d.frames.push_back(std::move(frames));
    }

    // One frame in memory at a time, however many the dataset lists: the
    // byte sums are exact integers, so the mean is the reference's.
    for (const auto& group : background_frames) {
        std::vector<std::uint64_t> sum(std::size_t(d.height) * d.width * 3, 0);
        for (const DatasetFrame* f : group) {
            const Frame frame = load_frame(dataset, sensor, *f);
            for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += frame.pixels[i];
        }
        Image mean(d.height, d.width, 3);
        const double scale = 1.0 / (255.0 * double(group.size()));
        for (std::size_t i = 0; i < sum.size(); ++i) mean.data[i] = float(double(sum[i]) * scale);
        d.backgrounds.push_back(std::move(mean));
    }
    return d;
}

}  // namespace vkfuse::study

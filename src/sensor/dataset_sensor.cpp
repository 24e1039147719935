// DatasetSensor: a recorded sensor played back frame by frame.
#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse {
namespace {

// The frames of one setting in the order they are played, and how far along.
struct Playlist {
    std::vector<const DatasetFrame*> frames;
    std::size_t next = 0;
    std::size_t background = 0;  // the first `background` frames come from background takes
};

std::string known_objects(const DatasetSensorRecord& s) {
    std::string out;
    for (const DatasetTake& t : s.takes)
        if (!t.background && out.find(t.object) == std::string::npos) out += (out.empty() ? "" : ", ") + t.object;
    return out.empty() ? "none" : out;
}

}  // namespace

struct DatasetSensor::Impl {
    std::shared_ptr<const Dataset> dataset;
    const DatasetSensorRecord* record = nullptr;
    std::string object;
    std::map<std::string, Playlist> playlists;  // by setting text
    Playlist* current = nullptr;
    std::string current_setting;
    std::map<const DatasetFrame*, Frame> decoded;  // preload()

    void add_takes(bool background) {
        for (const DatasetTake& t : record->takes) {
            if (t.background != background || (!background && t.object != object)) continue;
            for (const DatasetFrame& f : t.frames) {
                Playlist& p = playlists[f.illumination.to_string()];
                p.frames.push_back(&f);
                if (background) ++p.background;
            }
        }
    }
    // "<serial>: <problem> (<directory>, <object>)": the serial first, like every sensor error.
    std::string error(const std::string& problem) const {
        return record->info.serial + ": " + problem + " (" + dataset->directory + ", " + object + ")";
    }
};

DatasetSensor::DatasetSensor(std::shared_ptr<const Dataset> dataset, const std::string& serial,
                             const std::string& object)
    : impl_(std::make_unique<Impl>()) {
    auto& im = *impl_;
    im.dataset = std::move(dataset);
    im.record = &im.dataset->sensor(serial);
    im.object = object;
    const bool known = std::any_of(im.record->takes.begin(), im.record->takes.end(),
                                   [&](const DatasetTake& t) { return !t.background && t.object == object; });
    if (!known)
        throw Error(ErrorKind::InvalidArgument, serial + ": " + im.dataset->directory + " holds no frames of object '" +
                                                    object + "' (has " + known_objects(*im.record) + ")");
    im.add_takes(true);
    im.add_takes(false);
}

DatasetSensor::~DatasetSensor() = default;

SensorInfo DatasetSensor::info() const { return impl_->record->info; }

void DatasetSensor::set_illumination(const Illumination& setting) {
    auto& im = *impl_;
    setting.check(im.record->info.leds);
    auto it = im.playlists.find(setting.to_string());
    if (it == im.playlists.end())
        throw Error(ErrorKind::InvalidArgument, im.error("no frames recorded under LEDs " + setting.to_string()));
    im.current = &it->second;
    im.current_setting = setting.to_string();
}

Frame DatasetSensor::grab() {
    auto& im = *impl_;
    if (!im.current) {  // nothing requested yet: play the setting recorded first
        for (const DatasetTake& t : im.record->takes)
            if (!t.frames.empty() && !im.current) set_illumination(t.frames.front().illumination);
        if (!im.current) throw Error(ErrorKind::InvalidArgument, im.error("no frames recorded"));
    }
    if (im.current->next == im.current->frames.size())
        throw Error(ErrorKind::InvalidArgument,
                    im.error("all " + std::to_string(im.current->frames.size()) + " frames recorded under LEDs " +
                             im.current_setting + " played"));
    const DatasetFrame* f = im.current->frames[im.current->next++];
    if (auto it = im.decoded.find(f); it != im.decoded.end()) return it->second;
    return load_frame(*im.dataset, *im.record, *f);
}

std::size_t DatasetSensor::frames() const {
    std::size_t n = 0;
    for (const auto& [setting, p] : impl_->playlists) n += p.frames.size();
    return n;
}

void DatasetSensor::preload() {
    auto& im = *impl_;
    for (const auto& [setting, p] : im.playlists)
        for (const DatasetFrame* f : p.frames)
            if (!im.decoded.count(f)) im.decoded.emplace(f, load_frame(*im.dataset, *im.record, *f));
}

std::size_t DatasetSensor::frames_lit_by(const Illumination& setting, bool background) const {
    auto it = impl_->playlists.find(setting.to_string());
    if (it == impl_->playlists.end()) return 0;
    return background ? it->second.background : it->second.frames.size() - it->second.background;
}

std::size_t DatasetSensor::cycles_available(const IlluminationSequence& sequence) const {
    // Frames recorded by cycle, each cycle lit by exactly this sequence's
    // settings: the replay spans every recorded cycle, missed ones included.
    std::map<std::int64_t, std::multiset<std::string>> by_cycle;
    bool tagged = true;
    for (const DatasetTake& t : impl_->record->takes)
        if (!t.background && t.object == impl_->object)
            for (const DatasetFrame& f : t.frames) {
                tagged = tagged && f.cycle >= 0;
                by_cycle[f.cycle].insert(f.illumination.to_string());
            }
    std::multiset<std::string> settings;
    for (const Illumination& s : sequence) settings.insert(s.to_string());
    tagged = tagged && !by_cycle.empty() &&
             std::all_of(by_cycle.begin(), by_cycle.end(), [&](const auto& c) { return c.second == settings; });
    if (tagged) {
        // Only cycles the manifest accounts for, each delivered or missed:
        // a stray cycle number (2^53, say) never makes a replay run for ever.
        std::set<std::int64_t> accounted;
        for (const auto& c : by_cycle) accounted.insert(c.first);
        for (const DatasetMiss& m : impl_->record->missed) accounted.insert(m.cycle);
        const std::int64_t last_cycle = *accounted.rbegin();
        return std::int64_t(accounted.size()) == last_cycle + 1 ? std::size_t(last_cycle) + 1 : by_cycle.size();
    }
    std::map<std::string, std::size_t> uses;
    for (const Illumination& s : sequence) ++uses[s.to_string()];
    std::size_t cycles = sequence.empty() ? 0 : std::numeric_limits<std::size_t>::max();
    for (const auto& [setting, n] : uses)
        cycles = std::min(cycles, frames_lit_by(Illumination::parse(setting), false) / n);
    return cycles;
}

}  // namespace vkfuse

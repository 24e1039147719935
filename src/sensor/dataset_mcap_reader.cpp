// A dataset read from an MCAP recording (dataset_mcap.hpp): the manifest from
// its vkfuse.dataset metadata, the frames and misses from its messages, every
// one checked against the sensors the manifest declares.
#include <algorithm>
#include <limits>

#include "io/json_value.hpp"
#include "io/path_component.hpp"
#include "sensor/dataset_manifest.hpp"
#include "sensor/dataset_mcap.hpp"
#include "sensor/recording_messages.hpp"
#include "sensor/ros2_schema.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::sensor {
namespace {

constexpr std::size_t kMaxManifestBytes = std::size_t(16) << 20;  // frames are messages: sensors and a run only
constexpr std::int64_t kMaxCycle = std::int64_t(1) << 53;

// What a channel carries for the dataset, decided once per channel.
struct Route {
    enum Kind { Ignored, Frames, Misses } kind = Ignored;
    std::size_t sensor = 0;
};

class McapDatasetReader {
public:
    explicit McapDatasetReader(const std::string& path)
        : path_(path), storage_(std::make_shared<DatasetStorage>(path)) {}

    Dataset read() {
        io::mcap::Reader& r = storage_->reader;
        io::mcap::Reader::Visitor visitor;
        visitor.metadata = [&](const std::string& name, const std::map<std::string, std::string>& entries) {
            if (name == recording::kMetadataName) take_manifest(entries);
        };
        visitor.message = [&](const io::mcap::Message& m) { take_message(m); };
        const std::string stopped = r.scan(visitor);
        if (!dataset_) {
            if (!stopped.empty()) fail(stopped);
            fail("not a vkfuse recording (no \"vkfuse.dataset\" metadata record)");
        }
        if (!stopped.empty()) keep_whole_cycles(stopped);
        dataset_->storage = storage_;
        return std::move(*dataset_);
    }

private:
    [[noreturn]] void fail(const std::string& why) const { throw Error(ErrorKind::Format, path_ + ": " + why); }

    void take_manifest(const std::map<std::string, std::string>& entries) {
        if (dataset_) fail("two \"vkfuse.dataset\" metadata records");
        const auto it = entries.find(std::string(recording::kManifestKey));
        if (it == entries.end()) fail("the \"vkfuse.dataset\" metadata record has no \"manifest\"");
        if (it->second.size() > kMaxManifestBytes) fail("the \"vkfuse.dataset\" manifest is larger than 16 MiB");
        const std::string where = path_ + ": vkfuse.dataset";
        Dataset d = dataset_from_json(json::parse(it->second, where), where, path_);
        check_unique_serials(d, where);
        for (const DatasetSensorRecord& s : d.sensors)
            if (!s.takes.empty() || !s.missed.empty())
                fail("vkfuse.dataset: sensor " + s.info.serial + " lists frames (a recording holds them as messages)");
        dataset_ = std::move(d);
    }

    Route route_of(const io::mcap::Message& m) {
        if (const auto it = routes_.find(m.channel); it != routes_.end()) return it->second;
        const io::mcap::ChannelInfo& c = *storage_->reader.channel(m.channel);
        Route route;
        for (std::size_t i = 0; i < dataset_->sensors.size(); ++i) {
            const std::string& serial = dataset_->sensors[i].info.serial;
            if (c.topic == recording::frame_topic(serial)) route = {Route::Frames, i};
            if (c.topic == recording::metrics_topic(serial)) route = {Route::Misses, i};
        }
        if (route.kind != Route::Ignored) {
            const std::string_view type = route.kind == Route::Frames ? recording::kFrameType : recording::kMetricsType;
            const io::mcap::SchemaInfo* s = storage_->reader.schema(c.schema);
            if (!s || s->name != type || s->encoding != "ros2msg" || c.encoding != "cdr" || s->data != ros2msg_schema(type))
                fail("channel " + c.topic + ": schema " + (s ? s->name.substr(0, 100) + " (" + s->encoding.substr(0, 20) + ")" : "none") +
                     " in " + c.encoding.substr(0, 20) + ", not vkfuse's " + std::string(type) + " (ros2msg, cdr)");
        }
        routes_[m.channel] = route;
        return route;
    }

    void take_message(const io::mcap::Message& m) {
        if (!dataset_) {
            // Before the manifest only another program's topics may come.
            const std::string& topic = storage_->reader.channel(m.channel)->topic;
            if (topic.rfind("/vkfuse/", 0) == 0) fail("a message on " + topic.substr(0, 200) + " before the \"vkfuse.dataset\" metadata record");
            return;
        }
        const Route route = route_of(m);
        if (route.kind == Route::Ignored) return;
        DatasetSensorRecord& s = dataset_->sensors[route.sensor];
        const std::string where = "message " + std::to_string(m.sequence) + " on " + storage_->reader.channel(m.channel)->topic;
        std::string why;
        if (route.kind == Route::Misses) {
            std::string serial;
            const auto miss = recording::decode_miss(m.data, serial, why);
            if (!why.empty()) fail(where + ": " + why);
            if (!miss) return;
            if (serial != s.info.serial) fail(where + ": serial " + serial.substr(0, 100) + ", not " + s.info.serial);
            s.missed.push_back(*miss);
            return;
        }
        const auto f = recording::decode_frame(m.data, why);
        if (!f) fail(where + ": " + why);
        if (f->serial != s.info.serial) fail(where + ": serial " + f->serial.substr(0, 100) + ", not " + s.info.serial);
        if (f->height != s.info.height || f->width != s.info.width)
            fail(where + ": " + std::to_string(f->width) + "x" + std::to_string(f->height) + " frame, sensor " +
                 s.info.serial + " is " + std::to_string(s.info.width) + "x" + std::to_string(s.info.height));
        if (std::string p = io::component_problem(f->object); !p.empty()) fail(where + ": object: " + p);
        if (f->cycle < -1 || f->cycle > kMaxCycle) fail(where + ": cycle " + std::to_string(f->cycle));
        try {
            f->illumination.check(s.info.leds);
        } catch (const Error& e) {
            fail(where + ": " + e.what());
        }
        DatasetFrame frame;
        frame.index = f->index;
        frame.timestamp = f->timestamp;
        frame.illumination = f->illumination;
        frame.cycle = f->cycle;
        frame.chunk = m.at.chunk;
        frame.record = m.at.record;
        take_of(s, f->object, f->background).frames.push_back(std::move(frame));
    }

    // A recording cut short in the middle of a cycle: the cycles every
    // sensor reached, less the last of them (which the cut may have split).
    void keep_whole_cycles(const std::string& stopped) {
        Dataset& d = *dataset_;
        std::int64_t reached = std::numeric_limits<std::int64_t>::max();
        bool cycles = false;
        for (const DatasetSensorRecord& s : d.sensors) {
            std::int64_t last = -1;
            for (const DatasetTake& t : s.takes)
                for (const DatasetFrame& f : t.frames) last = std::max(last, f.cycle);
            for (const DatasetMiss& m : s.missed) last = std::max(last, m.cycle);
            cycles = cycles || last >= 0;
            reached = std::min(reached, last);
        }
        std::size_t kept = 0;
        for (DatasetSensorRecord& s : d.sensors) {
            for (DatasetTake& t : s.takes) {
                if (cycles)
                    std::erase_if(t.frames, [&](const DatasetFrame& f) { return f.cycle >= 0 && f.cycle >= reached; });
                kept += t.frames.size();
            }
            std::erase_if(s.missed, [&](const DatasetMiss& m) { return m.cycle >= reached; });
        }
        d.incomplete = path_ + ": " + stopped + "; using the " + std::to_string(kept) + " frames before it" +
                       (cycles ? " (" + std::to_string(std::max<std::int64_t>(reached, 0)) + " whole cycles)" : "");
    }

    std::string path_;
    std::shared_ptr<DatasetStorage> storage_;
    std::optional<Dataset> dataset_;
    std::map<std::uint16_t, Route> routes_;
};

}  // namespace

Dataset read_mcap_dataset(const std::string& path) { return McapDatasetReader(path).read(); }

Frame load_mcap_frame(const Dataset& dataset, const DatasetSensorRecord& sensor, const DatasetFrame& frame) {
    const io::mcap::Message m = dataset.storage->reader.read({frame.chunk, frame.record});
    std::string why;
    const auto f = recording::decode_frame(m.data, why);
    const std::string where = dataset.directory + ": " + sensor.info.serial + " frame " + std::to_string(frame.index);
    if (!f) throw Error(ErrorKind::Format, where + ": " + why);
    if (f->height != sensor.info.height || f->width != sensor.info.width || f->index != frame.index)
        throw Error(ErrorKind::Format, where + ": changed since the recording was read");
    Frame out;
    out.index = frame.index;
    out.timestamp = frame.timestamp;
    out.height = f->height;
    out.width = f->width;
    out.illumination = frame.illumination;
    out.recorded_cycle = frame.cycle;
    out.pixels.assign(f->pixels.begin(), f->pixels.end());
    return out;
}

}  // namespace vkfuse::sensor

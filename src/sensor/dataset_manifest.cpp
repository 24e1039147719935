#include "sensor/dataset_manifest.hpp"

#include <cmath>
#include <limits>

#include "io/path_component.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::sensor {
namespace {

using json::Value;

Value leds_json(const LedLayout& leds) {
    Value::Array names(leds.names.begin(), leds.names.end());
    return Value::Object{
        {"model", leds.model}, {"channels", leds.channels}, {"max_level", leds.max_level}, {"names", std::move(names)}};
}

Value frame_json(const DatasetFrame& f) {
    Value::Object o{
        {"file", f.file}, {"index", f.index}, {"timestamp", f.timestamp}, {"illumination", f.illumination.to_string()}};
    if (f.cycle >= 0) o.emplace_back("cycle", f.cycle);
    return o;
}

Value sensor_json(const DatasetSensorRecord& s) {
    Value::Array takes;
    for (const DatasetTake& t : s.takes) {
        Value::Array frames;
        for (const DatasetFrame& f : t.frames) frames.push_back(frame_json(f));
        takes.push_back(
            Value::Object{{"object", t.object}, {"background", t.background}, {"frames", std::move(frames)}});
    }
    Value::Object o{{"serial", s.info.serial}, {"model", s.info.model}, {"width", s.info.width},
                    {"height", s.info.height}, {"fps", s.info.fps},     {"leds", leds_json(s.info.leds)},
                    {"takes", std::move(takes)}};
    if (!s.missed.empty()) {
        Value::Array missed;
        for (const DatasetMiss& m : s.missed)
            missed.push_back(Value::Object{{"cycle", m.cycle}, {"status", m.status}, {"error", m.error}});
        o.emplace_back("missed", std::move(missed));
    }
    return o;
}

Value run_json(const DatasetRun& r) {
    const FusionSpec& f = r.fusion;
    return Value::Object{{"sequence", to_string(r.sequence)},
                         {"method", std::string(to_string(f.method))},
                         {"levels", f.levels},
                         {"wavelet", std::string(to_string(f.wavelet))},
                         {"mode", std::string(to_string(f.mode))},
                         {"base_rule", std::string(to_string(f.base_rule))},
                         {"detail_rule", std::string(to_string(f.detail_rule))},
                         {"background_frames", r.background_frames},
                         {"window", std::string(to_string(r.window))}};
}

// A value at a path in the manifest; every accessor names the path when the
// value is missing or of the wrong kind.
class Node {
public:
    Node(const Value& v, std::string path, const std::string& file) : v_(v), path_(std::move(path)), file_(file) {}

    [[noreturn]] void fail(const std::string& problem) const {
        throw Error(ErrorKind::Format, file_ + ": " + (path_.empty() ? "" : path_ + ": ") + problem);
    }
    Node operator[](const char* key) const {
        if (!v_.is_object()) fail("expected an object");
        const Value* m = v_.find(key);
        const std::string path = path_.empty() ? key : path_ + "." + key;
        if (!m) Node(v_, path, file_).fail("missing");
        return Node(*m, path, file_);
    }
    bool has(const char* key) const { return v_.find(key) != nullptr; }
    std::vector<Node> items() const {
        if (!v_.is_array()) fail("expected an array");
        std::vector<Node> out;
        for (std::size_t i = 0; i < v_.array().size(); ++i)
            out.emplace_back(v_.array()[i], path_ + "[" + std::to_string(i) + "]", file_);
        return out;
    }
    const std::string& text() const {
        if (!v_.is_string()) fail("expected a string");
        return v_.string();
    }
    double number() const {
        if (!v_.is_number()) fail("expected a number");
        return v_.number();
    }
    bool boolean() const {
        if (!v_.is_bool()) fail("expected true or false");
        return v_.boolean();
    }
    std::int64_t integer(std::int64_t lo, std::int64_t hi) const {
        const double d = number();
        if (d != std::floor(d) || d < double(lo) || d > double(hi))
            fail("expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
        return std::int64_t(d);
    }
    // Anything the library parses from text (a setting, a method name): its
    // own message, prefixed with where it was found.
    template <class Parse>
    auto parsed(Parse parse) const -> decltype(parse(std::string())) {
        try {
            return parse(text());
        } catch (const Error& e) {
            fail(e.what());
        }
    }

private:
    const Value& v_;
    std::string path_;
    const std::string& file_;
};

constexpr std::int64_t kMaxSide = 1 << 16;
constexpr std::int64_t kMaxIndex = std::int64_t(1) << 53;  // exact in a double
constexpr std::size_t kMaxMessageBytes = 4096;

LedLayout leds_from(const Node& n) {
    LedLayout l;
    l.model = n["model"].text();
    l.channels = int(n["channels"].integer(1, 1024));
    l.max_level = int(n["max_level"].integer(1, 65535));
    for (const Node& name : n["names"].items()) l.names.push_back(name.text());
    if (int(l.names.size()) != l.channels) n["names"].fail("expected one name per LED channel");
    return l;
}

DatasetFrame frame_from(const Node& n, const LedLayout& leds) {
    DatasetFrame f;
    f.file = n["file"].text();
    if (!io::is_contained_relative_path(f.file))
        n["file"].fail("expected a relative path inside the dataset (plain components, no '.' or '..')");
    f.index = std::uint64_t(n["index"].integer(0, kMaxIndex));
    f.timestamp = n["timestamp"].number();
    f.illumination = n["illumination"].parsed([&](const std::string& s) {
        Illumination i = Illumination::parse(s);
        i.check(leds);
        return i;
    });
    if (n.has("cycle")) f.cycle = n["cycle"].integer(0, kMaxIndex);
    return f;
}

DatasetSensorRecord sensor_from(const Node& n) {
    DatasetSensorRecord s;
    s.info.serial = n["serial"].text();
    // Serials and object names become directory and file names of a run's
    // output: one plain component each, whatever the manifest says.
    if (std::string why = io::component_problem(s.info.serial); !why.empty()) n["serial"].fail(why);
    s.info.model = n["model"].text();
    s.info.width = int(n["width"].integer(1, kMaxSide));
    s.info.height = int(n["height"].integer(1, kMaxSide));
    s.info.fps = n["fps"].number();
    s.info.leds = leds_from(n["leds"]);
    for (const Node& t : n["takes"].items()) {
        DatasetTake take;
        take.object = t["object"].text();
        if (std::string why = io::component_problem(take.object); !why.empty()) t["object"].fail(why);
        take.background = t["background"].boolean();
        for (const Node& f : t["frames"].items()) take.frames.push_back(frame_from(f, s.info.leds));
        s.takes.push_back(std::move(take));
    }
    if (n.has("missed"))
        for (const Node& m : n["missed"].items()) {
            DatasetMiss miss;
            miss.cycle = m["cycle"].integer(0, kMaxIndex);
            miss.status = m["status"].text();
            if (miss.status != "timeout" && miss.status != "failed") m["status"].fail("expected timeout or failed");
            miss.error = m["error"].text();
            if (miss.error.size() > kMaxMessageBytes) m["error"].fail("longer than 4096 bytes");
            s.missed.push_back(std::move(miss));
        }
    return s;
}

DatasetRun run_from(const Node& n) {
    DatasetRun r;
    r.sequence = n["sequence"].parsed([](const std::string& s) { return parse_sequence(s); });
    r.fusion.method = n["method"].parsed([](const std::string& s) { return parse_method(s); });
    r.fusion.levels = int(n["levels"].integer(0, 64));
    r.fusion.wavelet = n["wavelet"].parsed([](const std::string& s) { return parse_wavelet(s); });
    r.fusion.mode = n["mode"].parsed([](const std::string& s) { return parse_wavelet_mode(s); });
    r.fusion.base_rule = n["base_rule"].parsed([](const std::string& s) { return parse_rule(s); });
    r.fusion.detail_rule = n["detail_rule"].parsed([](const std::string& s) { return parse_rule(s); });
    r.background_frames = int(n["background_frames"].integer(0, 1 << 20));
    if (n.has("window"))  // recordings made before sliding windows: cycles
        r.window = n["window"].parsed([](const std::string& s) { return parse_fusion_window(s, "window"); });
    return r;
}

}  // namespace

DatasetTake& take_of(DatasetSensorRecord& s, const std::string& object, bool background) {
    for (DatasetTake& t : s.takes)
        if (t.object == object && t.background == background) return t;
    s.takes.push_back({object, background, {}});
    return s.takes.back();
}

void check_unique_serials(const Dataset& d, const std::string& file) {
    for (std::size_t i = 0; i < d.sensors.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (d.sensors[i].info.serial == d.sensors[j].info.serial)
                throw Error(ErrorKind::Format, file + ": sensor " + d.sensors[i].info.serial + " listed twice");
}

json::Value manifest_json(const Dataset& d) {
    Value::Array sensors;
    for (const DatasetSensorRecord& s : d.sensors) sensors.push_back(sensor_json(s));
    Value::Object o{{"format", kDatasetFormat}, {"version", kDatasetVersion}, {"source", d.source}};
    if (d.run) o.emplace_back("run", run_json(*d.run));
    o.emplace_back("sensors", std::move(sensors));
    return o;
}

Dataset dataset_from_json(const Value& manifest, const std::string& file, const std::string& directory) {
    const Node root(manifest, "", file);
    if (root["format"].text() != kDatasetFormat)
        root["format"].fail(std::string("expected \"") + kDatasetFormat + "\"");
    if (root["version"].integer(1, std::numeric_limits<int>::max()) != kDatasetVersion)
        root["version"].fail("unsupported version (this vkfuse reads " + std::to_string(kDatasetVersion) + ")");
    Dataset d;
    d.directory = directory;
    d.source = root["source"].text();
    if (root.has("run")) d.run = run_from(root["run"]);
    for (const Node& s : root["sensors"].items()) d.sensors.push_back(sensor_from(s));
    return d;
}

}  // namespace vkfuse::sensor

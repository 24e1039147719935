// The live server's channels and messages (live_channels.hpp).
#include "serve/live_channels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "io/cdr.hpp"
#include "io/json_value.hpp"
#include "io/png.hpp"
#include "vkfuse/core/error.hpp"
#include "sensor/frame_codec.hpp"
#include "sensor/ros2_names.hpp"
#include "sensor/ros2_schema.hpp"

namespace vkfuse::cli::serve {
namespace {

constexpr double kStatusWindowSeconds = 5.0;
// What a person looking at the gel sees no loss in; a tenth of the raw bytes.
constexpr int kJpegQuality = 90;

const char* kMetricsSchema = R"({"title": "vkfuse.Metrics", "description": "One sensor's cycle: the metrics.jsonl line of vkfuse run --out", "type": "object",
 "properties": {"cycle": {"type": "integer"}, "sensor": {"type": "string"}, "status": {"type": "string"},
  "sharpness": {"type": ["number", "null"]}, "contrast": {"type": ["number", "null"]}, "background_diff": {"type": ["number", "null"]},
  "idle": {"type": "boolean"}, "reused": {"type": "boolean"}, "fused_fraction": {"type": "number"}}})";
const char* kStatusSchema = R"({"title": "vkfuse.RigStatus", "type": "object",
 "properties": {"cycle": {"type": "integer"}, "cycles_per_s": {"type": "number"}, "fused_fraction": {"type": "number"},
  "idle_fraction": {"type": "number"}, "reused_fraction": {"type": "number"}, "ms_capture": {"type": "number"},
  "ms_fuse": {"type": "number"}, "sensors": {"type": "array"}, "errors": {"type": "array"}}})";
const char* kRigSchema = R"({"title": "vkfuse.Rig", "type": "object",
 "properties": {"sensors": {"type": "array"}, "sequence": {"type": "array"}, "method": {"type": "string"},
  "object": {"type": "string"}, "static_slot": {"type": "integer"}}})";

// A std_msgs/Header stamped at.
void header(io::cdr::Writer& w, const std::string& frame_id, std::chrono::system_clock::time_point at) {
    w.header(std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(at.time_since_epoch()).count()), frame_id);
}

std::string setting_token(const Illumination& s) {
    std::string t = "led";
    for (int l : s.levels()) t += "_" + std::to_string(l);
    return t;
}

}  // namespace

LiveChannels::LiveChannels(const LiveRig& rig) : rig_(rig) {
    const std::string image_schema = sensor::ros2msg_schema("sensor_msgs/msg/Image");
    const std::string compressed_schema = sensor::ros2msg_schema("sensor_msgs/msg/CompressedImage");
    auto add = [&](std::string topic, ChannelRole role, const std::string& encoding, const std::string& name,
                   const std::string& schema) {
        Channel c;
        c.id = std::uint32_t(channels_.size() + 1);
        c.topic = std::move(topic);
        c.encoding = encoding;
        c.schema_name = name;
        c.schema = schema;
        c.schema_encoding = encoding == "cdr" ? "ros2msg" : "jsonschema";
        channels_.push_back(std::move(c));
        roles_.push_back(role);
    };
    for (std::size_t i = 0; i < rig.sensors.size(); ++i) {
        const std::string base = "/vkfuse/" + sensor::ros2_topic_token(rig.sensors[i].serial);
        add(base + "/fused", {ChannelRole::Fused, i, 0}, "cdr", "sensor_msgs/msg/Image", image_schema);
        add(base + "/fused/compressed", {ChannelRole::FusedPng, i, 0}, "cdr", "sensor_msgs/msg/CompressedImage",
            compressed_schema);
        for (std::size_t k = 0; k < rig.sequence.size(); ++k)
            add(base + "/lit/" + setting_token(rig.sequence[k]), {ChannelRole::Lit, i, k}, "cdr",
                "sensor_msgs/msg/Image", image_schema);
        for (std::size_t k = 0; k < rig.sequence.size(); ++k)
            add(base + "/lit/" + setting_token(rig.sequence[k]) + "/compressed", {ChannelRole::LitJpeg, i, k}, "cdr",
                "sensor_msgs/msg/CompressedImage", compressed_schema);
        add(base + "/metrics", {ChannelRole::Metrics, i, 0}, "json", "vkfuse.Metrics", kMetricsSchema);
    }
    add("/vkfuse/status", {ChannelRole::Status, 0, 0}, "json", "vkfuse.RigStatus", kStatusSchema);
    add("/vkfuse/rig", {ChannelRole::Rig, 0, 0}, "json", "vkfuse.Rig", kRigSchema);
}

std::string LiveChannels::rig_json() const {
    json::Value::Array sensors, sequence;
    for (const SensorInfo& s : rig_.sensors)
        sensors.push_back(json::Value::Object{{"serial", s.serial},
                                              {"token", sensor::ros2_topic_token(s.serial)},
                                              {"model", s.model},
                                              {"width", s.width},
                                              {"height", s.height},
                                              {"fps", s.fps}});
    for (const Illumination& s : rig_.sequence) sequence.push_back(s.to_string());
    return json::write(json::Value::Object{{"sensors", std::move(sensors)},
                                           {"sequence", std::move(sequence)},
                                           {"method", rig_.method},
                                           {"object", rig_.object},
                                           {"static_slot", std::uint64_t(rig_.static_slot)}});
}

std::string image_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, int height, int width,
                      const std::uint8_t* rgb) {
    io::cdr::Writer w;
    header(w, frame_id, at);
    w.num(std::uint32_t(height)).num(std::uint32_t(width)).str("rgb8").num(std::uint8_t(0)).num(std::uint32_t(width) * 3u);
    w.octets(rgb, std::size_t(height) * std::size_t(width) * 3);
    return w.take();
}

std::string jpeg_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, int height, int width,
                     const std::uint8_t* rgb) {
    const std::vector<std::uint8_t> jpeg =
        rgb_to_jpeg({rgb, std::size_t(height) * std::size_t(width) * 3}, width, height, kJpegQuality);
    io::cdr::Writer w;
    header(w, frame_id, at);
    w.str("jpeg").octets(jpeg.data(), jpeg.size());
    return w.take();
}

std::string image_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, const Image& fused) {
    const std::vector<unsigned char> rgb = io::to_8bit(fused);
    return image_cdr(frame_id, at, fused.height, fused.width, rgb.data());
}

std::string png_cdr(const std::string& frame_id, std::chrono::system_clock::time_point at, const Image& fused) {
    char* data = nullptr;
    std::size_t size = 0;
    std::FILE* memory = ::open_memstream(&data, &size);
    if (!memory) throw Error(ErrorKind::Io, frame_id + ": fused PNG: out of memory");
    try {
        io::write_png(memory, fused, frame_id + " (fused PNG)", io::PngSpeed::Fast);
    } catch (...) {
        std::fclose(memory);
        std::free(data);
        throw;
    }
    std::fclose(memory);
    io::cdr::Writer w;
    header(w, frame_id, at);
    w.str("png").octets(data, size);
    std::free(data);
    return w.take();
}

void RigStatus::add(const LiveCycle& cycle) {
    Seen seen{cycle.at};
    if (states_.size() != cycle.sensors.size()) {
        states_.assign(cycle.sensors.size(), "ok");
        late_.resize(cycle.sensors.size(), 0);
    }
    errors_.clear();
    for (std::size_t i = 0; i < cycle.sensors.size(); ++i) {
        const LiveCycle::Sensor& s = cycle.sensors[i];
        states_[i] = std::string(to_string(s.status));
        if (s.status == SensorStatus::Timeout) ++late_[i];
        if (!s.error.empty()) errors_.push_back(s.error);
        if (s.status != SensorStatus::Ok) continue;
        ++seen.delivered;
        seen.idle += s.idle;
        seen.reused += s.reused;
        seen.fused += !s.idle && !s.reused;
    }
    window_.push_back(seen);
    while (window_.size() > 2 && std::chrono::duration<double>(cycle.at - window_.front().at).count() > kStatusWindowSeconds)
        window_.erase(window_.begin());
    cycle_ = cycle.cycle;
    capture_wait_s_ = cycle.capture_wait_s;
    fuse_s_ = cycle.fuse_s;
}

std::string RigStatus::json() const {
    std::size_t delivered = 0, idle = 0, reused = 0, fused = 0;
    for (const Seen& s : window_) delivered += s.delivered, idle += s.idle, reused += s.reused, fused += s.fused;
    const double span = window_.size() > 1 ? std::chrono::duration<double>(window_.back().at - window_.front().at).count() : 0;
    const double rate = span > 0 ? double(window_.size() - 1) / span : 0;
    const auto share = [&](std::size_t n) { return delivered ? double(n) / double(delivered) : 0.0; };
    json::Value::Array sensors, errors;
    for (std::size_t i = 0; i < states_.size(); ++i)
        sensors.push_back(json::Value::Object{{"status", states_[i]}, {"late_cycles", late_[i]}});
    for (const std::string& e : errors_) errors.push_back(e);
    return json::write(json::Value::Object{{"cycle", cycle_},
                                           {"cycles_per_s", rate},
                                           {"fused_fraction", share(fused)},
                                           {"idle_fraction", share(idle)},
                                           {"reused_fraction", share(reused)},
                                           {"ms_capture", capture_wait_s_ * 1e3},
                                           {"ms_fuse", fuse_s_ * 1e3},
                                           {"sensors", std::move(sensors)},
                                           {"errors", std::move(errors)}});
}

}  // namespace vkfuse::cli::serve

// RigPublisher (vkfuse/ros2/publisher.hpp): a rig's cycles as ROS 2 messages,
// written through Cyclone DDS with the C types idlc generates from
// ros2/idl/*.idl and ros2/vkfuse_msgs/msg/*.msg (src/CMakeLists.txt). The
// messages point into the cycle's own data; DDS serializes them in dds_write.
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "diagnostic_msgs.h"
#include "io/png.hpp"
#include "ros2/dds_entities.hpp"
#include "ros2/job_thread.hpp"
#include "ros2/messages.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::ros2 {
namespace {

// History depths. Fused images and metrics are transient local: a
// subscriber gets the last cycles the moment it matches, even one that
// matched the instant the first cycle went out (discovery completes on the
// two sides at different times). Images are large, so only three of each
// sensor are kept (a 32FC3 VGA image is 3.7 MB); /vkfuse/rig keeps its one
// description. A volatile subscriber (ROS 2's default) matches them all.
constexpr int kImageDepth = 3, kMetricsDepth = 20, kDiagnosticsDepth = 10, kRigDepth = 1;
// Cycles as images; a fusion host that joins takes the last few at once.
// Each sensor's one background.
constexpr int kCycleDepth = 3, kBackgroundDepth = 1;
constexpr auto kDiagnosticsPeriod = std::chrono::seconds(1);
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The header of a message about the whole rig: stamped now, no frame.
std_msgs_msg_dds__Header_ rig_header() {
    static const std::string none;
    return {stamp_of(std::chrono::system_clock::now()), text(none)};
}

std::string status_text(const SensorCycle& s) {
    switch (s.status) {
        case SensorStatus::Ok: return "ok";
        case SensorStatus::Timeout: return "late: no new frames within the cycle timeout";
        case SensorStatus::Failed: return s.error;
    }
    return "";
}

std::uint8_t metrics_status(SensorStatus s) {
    switch (s) {
        case SensorStatus::Ok: return vkfuse_msgs_msg_dds__FusionMetrics_Constants_STATUS_OK;
        case SensorStatus::Timeout: return vkfuse_msgs_msg_dds__FusionMetrics_Constants_STATUS_TIMEOUT;
        case SensorStatus::Failed: return vkfuse_msgs_msg_dds__FusionMetrics_Constants_STATUS_FAILED;
    }
    return vkfuse_msgs_msg_dds__FusionMetrics_Constants_STATUS_FAILED;
}

}  // namespace

struct RigPublisher::Impl {
    RigTopics rig;
    PublisherOptions options;
    std::vector<std::string> tokens;
    std::string method;
    LedSettings settings;
    CaptureTime capture_time;
    DdsEntity domain;  // where the publisher made the process's domain (configured_domain); goes last
    DdsEntity participant;
    std::vector<DdsEntity> fused, metrics, cycles, backgrounds;  // fused, metrics: when the rig fuses
    DdsEntity diagnostics, description;
    std::optional<std::chrono::steady_clock::time_point> diagnosed;
    std::atomic<std::uint64_t> written{0}, dropped{0};
    // Per sensor, the background frames of the settings so far (touched only
    // by that sensor's thread), until every distinct setting has come.
    std::vector<std::vector<std::pair<Illumination, std::vector<Frame>>>> background_takes;
    const std::size_t distinct_settings;
    JobThread background_writer;  // last: it finishes before the writers go

    Impl(const RigTopics& r, const PublisherOptions& o, CaptureTime t)
        : rig(r),
          options(o),
          method(method_label(r.fusion)),
          settings(r.sequence),
          capture_time(std::move(t)),
          distinct_settings(vkfuse::distinct_settings(r.sequence).size()) {
        std::map<std::string, std::string> serial_of;
        for (const SensorInfo& s : rig.sensors) {
            const std::string token = topic_token(s.serial);
            if (auto [it, fresh] = serial_of.emplace(token, s.serial); !fresh)
                throw Error(ErrorKind::InvalidArgument, "--publish ros2: serials " + it->second + " and " + s.serial +
                                                            " both name topics /vkfuse/" + token);
            tokens.push_back(token);
        }
        domain = configured_domain(options.domain);
        participant = make_participant(options.domain);
        const TopicQos image_qos(kImageDepth, true), metrics_qos(kMetricsDepth, true),
            diagnostics_qos(kDiagnosticsDepth, false), rig_qos(kRigDepth, true), cycle_qos(kCycleDepth, true),
            background_qos(kBackgroundDepth, true);
        for (const std::string& token : tokens) {
            const std::string topic = "/vkfuse/" + token;
            if (rig.fused) {
                fused.push_back(make_writer(participant, sensor_msgs_msg_dds__Image__desc, topic + "/fused", image_qos));
                metrics.push_back(
                    make_writer(participant, vkfuse_msgs_msg_dds__FusionMetrics__desc, topic + "/metrics", metrics_qos));
            }
            if (options.frames) {
                cycles.push_back(make_writer(participant, vkfuse_msgs_msg_dds__LitCycle__desc, topic + "/cycle", cycle_qos));
                backgrounds.push_back(make_writer(participant, vkfuse_msgs_msg_dds__Background__desc,
                                                  topic + "/background", background_qos));
            }
        }
        background_takes.resize(tokens.size());
        converted.resize(tokens.size());
        diagnostics = make_writer(participant, diagnostic_msgs_msg_dds__DiagnosticArray__desc, "/diagnostics", diagnostics_qos);
        description = make_writer(participant, vkfuse_msgs_msg_dds__RigDescription__desc, "/vkfuse/rig", rig_qos);
        describe_rig();
    }

    void write(const DdsEntity& writer, const void* sample) {
        if (dds_write(writer.get(), sample) == DDS_RETCODE_OK)
            ++written;
        else
            ++dropped;
    }

    builtin_interfaces_msg_dds__Time_ stamp(std::size_t sensor, double timestamp) const {
        return stamp_of(capture_time ? capture_time(sensor, timestamp) : std::chrono::system_clock::now());
    }

    std::vector<builtin_interfaces_msg_dds__Time_> stamps(std::size_t sensor, const std::vector<Frame>& frames) const {
        std::vector<builtin_interfaces_msg_dds__Time_> out;
        for (const Frame& f : frames) out.push_back(stamp(sensor, f.timestamp));
        return out;
    }

    void publish_cycle(std::size_t i, std::uint64_t cycle, const SensorCycle& s,
                       const std::vector<builtin_interfaces_msg_dds__Time_>& frame_stamps,
                       const builtin_interfaces_msg_dds__Time_& stamp) {
        LitFrames frames(s.serial);
        for (std::size_t k = 0; k < s.frames.size(); ++k) frames.add(s.frames[k], frame_stamps[k], settings.messages.at(k));
        vkfuse_msgs_msg_dds__LitCycle_ msg{};
        msg.header = {stamp, text(s.serial)};
        msg.serial = text(s.serial);
        msg.cycle = cycle;
        msg.frames = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__LitFrame_>(frames.messages);
        write(cycles[i], &msg);
    }

    // A sensor's background goes out from background_writer: serializing
    // megabytes on the capture thread would hold its first cycles back,
    // and the rig's with them.
    void add_background(std::size_t i, const Illumination& setting, const std::vector<Frame>& frames) {
        auto& takes = background_takes.at(i);
        takes.emplace_back(setting, frames);
        if (takes.size() < distinct_settings) return;
        background_writer.push([this, i, whole = std::move(takes)] { write_background(i, whole); });
        takes.clear();
    }

    // One message of every setting's frames, in the order they came (the
    // sequence's), pointing at the frames taken.
    void write_background(std::size_t i, const std::vector<std::pair<Illumination, std::vector<Frame>>>& takes) {
        const SensorInfo& sensor = rig.sensors[i];
        LitFrames messages(sensor.serial);
        for (const auto& [taken, fs] : takes) {
            const auto k = std::size_t(std::find(rig.sequence.begin(), rig.sequence.end(), taken) - rig.sequence.begin());
            for (const Frame& f : fs) messages.add(f, stamp(i, f.timestamp), settings.messages.at(k));
        }
        vkfuse_msgs_msg_dds__Background_ msg{};
        msg.header = {messages.messages.empty() ? stamp_of(std::chrono::system_clock::now())
                                                : messages.messages.front().image.header.stamp,
                      text(sensor.serial)};
        msg.serial = text(sensor.serial);
        msg.frames_per_setting = std::uint32_t(takes.front().second.size());
        msg.frames = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__LitFrame_>(messages.messages);
        write(backgrounds[i], &msg);
    }

    void describe_rig() {
        std::vector<std::vector<char*>> channels;
        std::vector<vkfuse_msgs_msg_dds__SensorDescription_> sensors;
        for (std::size_t i = 0; i < rig.sensors.size(); ++i) {
            SensorInfo& s = rig.sensors[i];
            channels.emplace_back();
            for (const std::string& name : s.leds.names) channels.back().push_back(text(name));
        }
        for (std::size_t i = 0; i < rig.sensors.size(); ++i) {
            SensorInfo& s = rig.sensors[i];
            sensors.push_back({text(s.serial), text(tokens[i]), text(s.model), s.fps, std::uint32_t(s.width), std::uint32_t(s.height),
                               text(s.leds.model), sequence_of<dds_sequence_string>(channels[i]),
                               std::uint16_t(s.leds.max_level)});
        }
        std::vector<std::string> metric_names;
        for (Metric m : kAllMetrics)
            if (rig.metrics.has(m)) metric_names.emplace_back(to_string(m));
        std::vector<char*> metric_texts;
        for (const std::string& m : metric_names) metric_texts.push_back(text(m));
        const std::string skip(to_string(rig.skip.policy));
        vkfuse_msgs_msg_dds__RigDescription_ msg{};
        msg.header = rig_header();
        msg.sensors = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__SensorDescription_>(sensors);
        msg.settings = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__LedSetting_>(settings.messages);
        msg.method = text(method);
        msg.fused = rig.fused;
        msg.metrics = sequence_of<dds_sequence_string>(metric_texts);
        msg.skip = text(skip);
        msg.skip_threshold = rig.skip.threshold;
        msg.background_frames = std::uint32_t(rig.background_frames);
        msg.frames = options.frames;
        write(description, &msg);
    }

    // rgb8: the bytes of the image last converted, where the sensor's cycle
    // was not fused (idle or reused): a hand at rest publishes the same
    // image cycle after cycle, and comparing it costs less than converting it.
    struct Converted {
        std::vector<float> from;
        std::vector<std::uint8_t> bytes;
    };
    std::vector<Converted> converted;

    std::vector<std::uint8_t>& rgb8_of(std::size_t i, const SensorCycle& s) {
        const Image& image = *s.fused;
        Converted& c = converted.at(i);
        const bool unfused = s.skip.idle || s.skip.reused;
        if (unfused && c.from.size() == image.data.size() &&
            std::memcmp(c.from.data(), image.data.data(), image.data.size() * sizeof(float)) == 0)
            return c.bytes;
        c.bytes = io::to_8bit(image);
        if (unfused)
            c.from = image.data;
        else
            c.from = {};
        return c.bytes;
    }

    void publish_fused(std::size_t i, const SensorCycle& s, const builtin_interfaces_msg_dds__Time_& stamp) {
        const Image& image = *s.fused;
        std::vector<std::uint8_t> floats;
        if (options.encoding != ImageEncoding::Rgb8) {
            floats.resize(image.data.size() * sizeof(float));
            std::memcpy(floats.data(), image.data.data(), floats.size());
        }
        std::vector<std::uint8_t>& bytes = options.encoding == ImageEncoding::Rgb8 ? rgb8_of(i, s) : floats;
        const std::string encoding(to_string(options.encoding));
        sensor_msgs_msg_dds__Image_ msg{};
        msg.header = {stamp, text(s.serial)};
        msg.height = std::uint32_t(image.height);
        msg.width = std::uint32_t(image.width);
        msg.encoding = text(encoding);
        msg.is_bigendian = std::endian::native == std::endian::big;
        msg.step = std::uint32_t(bytes.size() / std::size_t(image.height));
        msg.data = sequence_of<dds_sequence_uint8>(bytes);
        write(fused[i], &msg);
    }

    void publish_metrics(std::size_t i, std::uint64_t cycle, const SensorCycle& s,
                         const builtin_interfaces_msg_dds__Time_& stamp) {
        const bool ok = s.status == SensorStatus::Ok;
        std::vector<vkfuse_msgs_msg_dds__LedSetting_> lit;
        if (ok)
            lit.assign(settings.messages.begin(),
                       settings.messages.begin() + std::ptrdiff_t(std::min(s.frames.size(), settings.messages.size())));
        vkfuse_msgs_msg_dds__FusionMetrics_ msg{};
        msg.header = {stamp, text(s.serial)};
        msg.serial = text(s.serial);
        msg.cycle = cycle;
        msg.status = metrics_status(s.status);
        msg.error = text(s.error);
        msg.method = text(method);
        msg.settings = sequence_of<dds_sequence_vkfuse_msgs_msg_dds__LedSetting_>(lit);
        msg.sharpness = ok ? s.metrics.sharpness : kNaN;
        msg.contrast = ok ? s.metrics.contrast : kNaN;
        msg.background_diff = ok && s.metrics.background_diff ? *s.metrics.background_diff : kNaN;
        msg.idle = ok && s.skip.idle;
        msg.reused = ok && s.skip.reused;
        msg.watch = ok && s.watch;
        msg.fused_fraction = ok ? s.skip.fused_fraction : 0;
        msg.changed_fraction = ok ? s.skip.changed_fraction : 0;
        msg.change_score = ok ? s.skip.score : 0;
        write(metrics[i], &msg);
    }

    // One status per sensor from this cycle, as stock ROS 2 tools
    // (rqt_robot_monitor, Foxglove's diagnostics panel) show them: level,
    // name, message, values.
    void publish_diagnostics(const CycleResult& cycle) {
        constexpr std::uint8_t kOk = 0, kWarn = 1, kError = 2;
        const std::size_t n = cycle.sensors.size();
        // The strings first, the messages pointing into them after: no
        // pointer is taken while a vector of strings still grows.
        std::vector<std::string> names, messages, statuses;
        const std::string cycle_key = "cycle", status_key = "status", idle_key = "idle";
        const std::string cycle_number = std::to_string(cycle.cycle), yes = "true", no = "false";
        for (const SensorCycle& s : cycle.sensors) {
            names.push_back("vkfuse: " + s.serial);
            messages.push_back(status_text(s));
            statuses.emplace_back(to_string(s.status));
        }
        std::vector<std::vector<diagnostic_msgs_msg_dds__KeyValue_>> values(n);
        std::vector<diagnostic_msgs_msg_dds__DiagnosticStatus_> status;
        for (std::size_t i = 0; i < n; ++i) {
            const SensorCycle& s = cycle.sensors[i];
            values[i] = {{text(cycle_key), text(cycle_number)}, {text(status_key), text(statuses[i])},
                         {text(idle_key), text(s.skip.idle ? yes : no)}};
            const std::uint8_t level = s.status == SensorStatus::Ok ? kOk : s.status == SensorStatus::Timeout ? kWarn : kError;
            status.push_back({level, text(names[i]), text(messages[i]), text(rig.sensors[i].serial),
                              sequence_of<dds_sequence_diagnostic_msgs_msg_dds__KeyValue_>(values[i])});
        }
        diagnostic_msgs_msg_dds__DiagnosticArray_ msg{};
        msg.header = rig_header();
        msg.status = sequence_of<dds_sequence_diagnostic_msgs_msg_dds__DiagnosticStatus_>(status);
        write(diagnostics, &msg);
    }
};

RigPublisher::RigPublisher(const RigTopics& rig, const PublisherOptions& options, CaptureTime capture_time)
    : impl_(std::make_unique<Impl>(rig, options, std::move(capture_time))) {}

// Subscribers still receiving the last cycles (a large image goes in many
// fragments) get them before the participant leaves: at most kLinger in all.
RigPublisher::~RigPublisher() {
    impl_->background_writer.finish();  // every background written before the wait for its acknowledgement
    constexpr auto kLinger = std::chrono::seconds(2);
    const auto deadline = std::chrono::steady_clock::now() + kLinger;
    // Backgrounds and the description too: a fusion host that lost a
    // fragment of either is still waiting for it.
    std::vector<const DdsEntity*> writers{&impl_->description, &impl_->diagnostics};
    for (const auto* group : {&impl_->backgrounds, &impl_->cycles, &impl_->fused, &impl_->metrics})
        for (const DdsEntity& w : *group) writers.push_back(&w);
    for (const DdsEntity* w : writers) {
        const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0 || dds_wait_for_acks(w->get(), left.count()) == DDS_RETCODE_TIMEOUT) break;
    }
}

void RigPublisher::publish(const CycleResult& cycle) {
    Impl& im = *impl_;
    if (cycle.sensors.size() != im.tokens.size())
        throw Error(ErrorKind::InvalidArgument, "ros2 publisher: a cycle of " + std::to_string(cycle.sensors.size()) +
                                                    " sensors for a rig of " + std::to_string(im.tokens.size()));
    for (std::size_t i = 0; i < cycle.sensors.size(); ++i) {
        const SensorCycle& s = cycle.sensors[i];
        const bool ok = s.status == SensorStatus::Ok && !s.frames.empty();
        const auto stamp = ok ? im.stamp(i, s.newest_timestamp()) : stamp_of(std::chrono::system_clock::now());
        if (!im.fused.empty()) {
            if (ok && s.fused) im.publish_fused(i, s, stamp);
            im.publish_metrics(i, cycle.cycle, s, stamp);
        }
        // A watch cycle (one setting) is no cycle a fusion host could fuse.
        if (!im.cycles.empty() && ok && s.frames.size() == im.rig.sequence.size())
            im.publish_cycle(i, cycle.cycle, s, im.stamps(i, s.frames), stamp);
    }
    const auto now = std::chrono::steady_clock::now();
    if (!im.diagnosed || now - *im.diagnosed >= kDiagnosticsPeriod) {
        im.publish_diagnostics(cycle);
        im.diagnosed = now;
    }
}

void RigPublisher::publish_background(std::size_t sensor, const Illumination& setting, const std::vector<Frame>& frames) {
    if (!impl_->backgrounds.empty()) impl_->add_background(sensor, setting, frames);
}

bool RigPublisher::has_subscribers(std::size_t sensor) const {
    for (const auto* group : {&impl_->fused, &impl_->metrics, &impl_->cycles, &impl_->backgrounds})
        if (!group->empty() && matched_subscribers(group->at(sensor)) == 0) return false;
    return true;
}

PublisherCounts RigPublisher::counts() const { return {impl_->written.load(), impl_->dropped.load()}; }

}  // namespace vkfuse::ros2

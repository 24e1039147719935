// RemoteRig (vkfuse/ros2/remote.hpp): the capture hosts' descriptions heard,
// and a RemoteSensor for each sensor asked for.
#include <chrono>
#include <cstdio>
#include <map>

#include "ros2/remote_sensor.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::ros2 {
namespace {

using Clock = std::chrono::steady_clock;

// Capture hosts whose descriptions the reader keeps until they are taken.
constexpr int kDescriptionDepth = 16;

void to_stderr(const std::string& line) { std::fprintf(stderr, "vkfuse: %s\n", line.c_str()); }

}  // namespace

struct RemoteRig::Impl {
    std::shared_ptr<RemoteDomain> domain = std::make_shared<RemoteDomain>();
    RemoteDescription description;
    std::vector<std::shared_ptr<RemoteSensor>> sensors;

    ~Impl() { domain->closing = true; }
};

RemoteRig::RemoteRig(const RemoteRigOptions& options) : impl_(std::make_shared<Impl>()) {
    RemoteDomain& d = *impl_->domain;
    d.report = options.report ? options.report : to_stderr;
    d.domain = configured_domain(options.domain);
    d.participant = make_participant(options.domain);
    const DdsEntity reader = make_reader(d.participant, vkfuse_msgs_msg_dds__RigDescription__desc, "/vkfuse/rig",
                                         TopicQos::reader(kDescriptionDepth));
    const DataWait described(d.participant, reader);

    // Serial -> what its capture host said, the first description of it heard.
    std::map<std::string, std::pair<SensorInfo, DescribedRig>> heard;
    std::vector<std::string> first_host;  // its sensors, when no serial was asked for
    std::string refused;
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(options.startup_timeout_s));
    auto complete = [&] {
        if (options.serials.empty()) return !first_host.empty();
        for (const std::string& s : options.serials)
            if (!heard.count(s)) return false;
        return true;
    };
    while (!complete()) {
        const LoanedSample<vkfuse_msgs_msg_dds__RigDescription_> sample(reader);
        if (sample.any()) {
            const auto& msg = sample.message();
            if (sample.valid() && msg.frames && !msg.fused) {
                DescribedRig rig;
                if (std::string p = check_description(msg, rig); !p.empty()) {
                    refused = p;
                    d.report("/vkfuse/rig: a capture host's description refused: " + p);
                } else {
                    std::vector<std::string> serials;
                    for (const SensorInfo& s : rig.sensors) {
                        serials.push_back(s.serial);
                        heard.try_emplace(s.serial, s, rig);
                    }
                    if (first_host.empty()) first_host = serials;
                }
            }
            continue;
        }
        if (Clock::now() >= deadline) {
            std::string missing;
            for (const std::string& s : options.serials)
                if (!heard.count(s)) missing += (missing.empty() ? "" : ", ") + s;
            throw Error(ErrorKind::Timeout,
                        "--source ros2: " +
                            (missing.empty() ? std::string("no capture host (vkfuse run --capture-only --publish ros2 "
                                                           "--publish-frames)")
                                             : "no capture host describes " + missing) +
                            " in ROS domain " + std::to_string(options.domain) + " within " +
                            seconds_text(options.startup_timeout_s) +
                            (refused.empty() ? "" : " (refused: " + refused + ")"));
        }
        described.wait(std::chrono::milliseconds(100));
    }

    const std::vector<std::string>& chosen = options.serials.empty() ? first_host : options.serials;
    RemoteDescription& out = impl_->description;
    for (const std::string& serial : chosen) {
        const auto& [info, rig] = heard.at(serial);
        if (out.sensors.empty()) {
            out.sequence = rig.sequence;
            out.background_frames = rig.background_frames;
        } else if (rig.sequence != out.sequence || rig.background_frames != out.background_frames) {
            throw Error(ErrorKind::InvalidArgument, "--source ros2: " + serial + " cycles through " +
                                                        to_string(rig.sequence) + " with " +
                                                        std::to_string(rig.background_frames) +
                                                        " background frames, " + out.sensors.front().serial + " through " +
                                                        to_string(out.sequence) + " with " +
                                                        std::to_string(out.background_frames) + ": one rig fuses one sequence");
        }
        out.sensors.push_back(info);
    }
    for (const SensorInfo& info : out.sensors)
        impl_->sensors.push_back(std::make_shared<RemoteSensor>(
            impl_->domain, SensorContract{info, out.sequence, out.background_frames}, options));
}

RemoteRig::~RemoteRig() = default;

const RemoteDescription& RemoteRig::description() const { return impl_->description; }

std::vector<RigSensor> RemoteRig::sensors() const {
    std::vector<RigSensor> out;
    for (const auto& s : impl_->sensors) out.push_back({s, s->clock()});
    return out;
}

RemoteCounts RemoteRig::counts(std::size_t sensor) const { return impl_->sensors.at(sensor)->counts(); }

}  // namespace vkfuse::ros2

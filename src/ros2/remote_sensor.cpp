// RemoteSensor (ros2/remote_sensor.hpp): a capture host's sensor, its
// background first, then whole cycles, every sample checked.
#include "ros2/remote_sensor.hpp"

#include <algorithm>
#include <thread>

#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"

namespace vkfuse::ros2 {
namespace {

using Clock = std::chrono::steady_clock;

// How long one wait lasts before the sensor looks at its publisher's
// liveliness and at closing again.
constexpr auto kSlice = std::chrono::milliseconds(100);
// A cycle-less second: the sensor is reported late (Error(Timeout)) and the
// rig goes on without it until it delivers.
constexpr auto kQuiet = std::chrono::seconds(1);

double system_seconds() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Whole cycles the sensor keeps: queue_cycles, as far as queue_bytes hold them, 1 at least.
int queue_depth(const SensorContract& contract, const RemoteRigOptions& options) {
    const std::uint64_t cycle_bytes =
        3ull * std::uint64_t(contract.info.width) * std::uint64_t(contract.info.height) * contract.sequence.size();
    return int(std::max<std::uint64_t>(
        1, std::min<std::uint64_t>(std::uint64_t(std::max(options.queue_cycles, 1)),
                                   options.queue_bytes / std::max<std::uint64_t>(cycle_bytes, 1))));
}

}  // namespace

double RemoteClock::now() const { return system_seconds() + offset_.load(); }

void RemoteClock::wait_until(double seconds) {
    const double left = seconds - now();
    if (left > 0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
}

RemoteSensor::RemoteSensor(std::shared_ptr<RemoteDomain> domain, SensorContract contract, const RemoteRigOptions& options)
    : domain_(std::move(domain)),
      contract_(std::move(contract)),
      topic_("/vkfuse/" + topic_token(contract_.info.serial)),
      startup_timeout_s_(options.startup_timeout_s),
      cycles_(make_reader(domain_->participant, vkfuse_msgs_msg_dds__LitCycle__desc, topic_ + "/cycle",
                          TopicQos::reader(queue_depth(contract_, options)))),
      background_(make_reader(domain_->participant, vkfuse_msgs_msg_dds__Background__desc, topic_ + "/background",
                              TopicQos::reader(1))),
      cycle_arrived_(domain_->participant, cycles_),
      background_arrived_(std::in_place, domain_->participant, background_),
      background_done_(contract_.background_frames == 0) {}

RemoteCounts RemoteSensor::counts() const {
    std::lock_guard lock(counts_mutex_);
    return counts_;
}

void RemoteSensor::say_now_and_then(const std::string& what) {
    const auto now = Clock::now();
    if (now - last_line_ < std::chrono::seconds(1)) return;
    last_line_ = now;
    domain_->report(contract_.info.serial + ": " + what);
}

void RemoteSensor::problem(const std::string& what) {
    {
        std::lock_guard lock(counts_mutex_);
        ++counts_.malformed;
    }
    say_now_and_then(what + " (" + topic_ + "; refused)");
}

// Its capture host: the participant that publishes it, which numbers the
// cycles of all that host's sensors (0 where DDS cannot say).
std::uint64_t RemoteSensor::participant_of(dds_instance_handle_t publication) const {
    dds_builtintopic_endpoint_t* endpoint = dds_get_matched_publication_data(cycles_.get(), publication);
    if (!endpoint) return 0;
    const std::uint64_t participant = endpoint->participant_instance_handle;
    dds_builtintopic_free_endpoint(endpoint);
    return participant;
}

std::optional<std::int32_t> RemoteSensor::live_publishers() const {
    dds_liveliness_changed_status_t status{};
    if (dds_get_liveliness_changed_status(cycles_.get(), &status) != DDS_RETCODE_OK) return std::nullopt;
    return status.alive_count;
}

Frame RemoteSensor::next_background_frame() {
    if (background_frames_.empty()) {
        const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                 std::chrono::duration<double>(startup_timeout_s_));
        for (;;) {
            if (domain_->closing) throw Error(ErrorKind::Timeout, contract_.info.serial + ": closing");
            LoanedSample<vkfuse_msgs_msg_dds__Background_> sample(background_);
            if (sample.valid()) {
                const std::string p = check_background(sample.message(), contract_, background_frames_);
                if (p.empty()) break;
                problem(p);
                continue;
            }
            if (sample.any()) continue;
            if (Clock::now() >= deadline)
                throw Error(ErrorKind::Timeout, contract_.info.serial + ": no background from its capture host within " +
                                                    seconds_text(startup_timeout_s_) + " (" + topic_ +
                                                    "/background)");
            background_arrived_->wait(kSlice);
        }
        background_served_.assign(background_frames_.size(), 0);
    }
    for (std::size_t s = 0; s < background_frames_.size(); ++s) {
        if (background_frames_[s].first != requested_ || background_served_[s] == background_frames_[s].second.size())
            continue;
        const std::size_t j = background_served_[s]++;
        bool all = true;
        for (std::size_t t = 0; t < background_frames_.size(); ++t)
            all = all && background_served_[t] == background_frames_[t].second.size();
        // The frames are freed once the capture thread has the last one.
        background_done_ = all;
        return std::move(background_frames_[s].second[j]);
    }
    throw Error(ErrorKind::InvalidArgument, contract_.info.serial + ": no background frame left under LEDs " +
                                                requested_.to_string());
}

std::optional<std::vector<Frame>> RemoteSensor::take_cycle() {
    LoanedSample<vkfuse_msgs_msg_dds__LitCycle_> sample(cycles_);
    if (!sample.valid()) return std::nullopt;
    const dds_instance_handle_t from = sample.info().publication_handle;
    const vkfuse_msgs_msg_dds__LitCycle_& msg = sample.message();
    if (publication_ != 0 && from != publication_) {
        if (live_publishers().value_or(0) > 1) {
            problem("a second publisher claims this serial while the first is alive");
            return std::nullopt;
        }
        last_cycle_.reset();  // the capture host started again: its cycles count from 0
    }
    std::vector<Frame> frames;
    if (std::string p = check_cycle(msg, contract_, frames); !p.empty()) {
        problem(p);
        return std::nullopt;
    }
    if (from != publication_) origin_ = participant_of(from);
    publication_ = from;
    if (last_cycle_ && msg.cycle <= *last_cycle_) {
        problem("cycle " + std::to_string(msg.cycle) + " after cycle " + std::to_string(*last_cycle_) +
                ": cycle numbers going backwards");
        return std::nullopt;
    }
    if (last_cycle_ && msg.cycle > *last_cycle_ + 1) {
        const std::uint64_t missed = msg.cycle - *last_cycle_ - 1;
        {
            std::lock_guard lock(counts_mutex_);
            counts_.missed += missed;
        }
        say_now_and_then(std::to_string(missed) + " cycle" + (missed > 1 ? "s" : "") + " before cycle " +
                         std::to_string(msg.cycle) + " never arrived whole (" + topic_ + "/cycle)");
    }
    last_cycle_ = msg.cycle;
    for (Frame& f : frames) {
        f.origin = origin_;
        f.origin_cycle = msg.cycle;
    }
    const builtin_interfaces_msg_dds__Time_& stamp = msg.frames._buffer[0].image.header.stamp;
    clock_->observe(frames.front().timestamp, double(stamp.sec) + double(stamp.nanosec) * 1e-9);
    std::lock_guard lock(counts_mutex_);
    ++counts_.cycles;
    return frames;
}

std::vector<Frame> RemoteSensor::next_cycle() {
    const auto quiet_until = Clock::now() + kQuiet;
    for (;;) {
        if (domain_->closing) throw Error(ErrorKind::Timeout, contract_.info.serial + ": closing");
        const std::optional<std::int32_t> live = live_publishers();
        const bool alive = live ? *live > 0 : alive_;
        if (alive_ && !alive) {
            alive_ = false;
            // Whoever publishes next, this host again or another, counts its cycles from its own start.
            publication_ = 0;
            last_cycle_.reset();
            {
                std::lock_guard lock(counts_mutex_);
                ++counts_.lost;
            }
            const std::string gone =
                contract_.info.serial + ": its capture host is gone (no live publisher of " + topic_ + "/cycle)";
            domain_->report(gone);
            away_ = true;
            throw Error(ErrorKind::Unplugged, gone);
        }
        alive_ = alive;
        if (std::optional<std::vector<Frame>> cycle = take_cycle()) {
            if (away_) domain_->report(contract_.info.serial + ": its capture host is back (" + topic_ + "/cycle)");
            away_ = false;
            return std::move(*cycle);
        }
        if (Clock::now() >= quiet_until) {
            if (!alive_)
                throw Error(ErrorKind::Unplugged, contract_.info.serial + ": no live publisher of " + topic_ + "/cycle");
            throw Error(ErrorKind::Timeout, contract_.info.serial + ": no cycle from its capture host for " +
                                                std::to_string(kQuiet.count()) + " s");
        }
        cycle_arrived_.wait(kSlice);
    }
}

Frame RemoteSensor::grab() {
    if (!background_done_) return next_background_frame();
    if (background_arrived_) {
        // The background is taken once (as a replugged DIGIT's): the reader
        // goes, so a capture host that restarts sends its latched
        // background, megabytes a sensor, to no one here.
        background_frames_ = {};
        background_arrived_.reset();
        background_ = {};
    }
    if (position_ == 0) cycle_ = next_cycle();
    const std::size_t k = position_;
    position_ = (position_ + 1) % cycle_.size();
    return std::move(cycle_[k]);
}

}  // namespace vkfuse::ros2

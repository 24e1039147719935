// Cyclone DDS entities with an owner, and the QoS ROS 2 gives its topics
// (rmw_cyclonedds_cpp's mapping of rmw_qos_profile_t).
#pragma once
#include <dds/dds.h>

#include <chrono>
#include <string>

namespace vkfuse::ros2 {

// An entity deleted with what it owns (a participant: its topics, writers
// and readers) when this goes.
class DdsEntity {
public:
    DdsEntity() = default;
    // Takes a dds_create_* result; a negative one throws Error(Device)
    // "<what>: <DDS's reason>".
    DdsEntity(dds_entity_t entity, const std::string& what);
    ~DdsEntity();
    DdsEntity(DdsEntity&& other) noexcept : entity_(other.entity_) { other.entity_ = 0; }
    DdsEntity& operator=(DdsEntity&& other) noexcept;
    DdsEntity(const DdsEntity&) = delete;
    DdsEntity& operator=(const DdsEntity&) = delete;
    dds_entity_t get() const { return entity_; }

private:
    dds_entity_t entity_ = 0;
};

// This process's DDS domain `domain`, made with vkfuse's settings unless
// something in the process made it first (then an empty entity: the
// domain lives as long as its maker). Deleting it deletes every participant
// in it, so it goes after them. Settings:
// - datagrams of up to 64 KB, where Cyclone sends 14.7 KB: a QVGA image is 4
//   datagrams rather than 16, and the sender's kernel work is mostly per
//   datagram (docs/measurements.md). A link that loses packets loses a whole
//   datagram with any of its IP fragments: there CYCLONEDDS_URI sets
//   <General><MaxMessageSize>14720B</MaxMessageSize></General> back (README,
//   "Lossy links");
// - receive buffers of 64 MB asked for: a cycle of a rig arrives as one
//   burst of datagrams (16 QVGA sensors, 2 settings: 7.4 MB), faster than a
//   busy receive thread drains them, and what overflows is repaired only a
//   heartbeat later while the cycle waits (the kernel grants at most twice
//   net.core.rmem_max: README, "Receive buffers");
// - then whatever CYCLONEDDS_URI configures (the interface, these two);
// - last, samples over kMaxSampleBytes refused, which nothing overrides.
DdsEntity configured_domain(int domain);

// Throws Error(InvalidArgument) "ROS domain N: expected 0..232" for a
// domain outside the RTPS port range.
void check_domain(int domain);
// A participant in ROS 2 domain `domain` (checked); Error(Device) names what DDS refused.
DdsEntity make_participant(int domain);

// How long a reliable writer may wait for a slow subscriber to acknowledge
// what it holds before the sample is dropped (and counted): Cyclone's own
// default. ROS 2 waits forever; a rig is held up by a stalled subscriber for
// this long at most per sample.
inline constexpr dds_duration_t kMaxBlocking = DDS_MSECS(100);

// ROS 2's QoS: reliable, keep last `depth`, volatile; `latched`: transient
// local, late subscribers get the last `depth` samples (as ROS 2's
// transient-local profile asks of the durability service).
class TopicQos {
public:
    TopicQos(int depth, bool latched);
    // A reader's: reliable, keep last `depth`, transient local (it takes
    // what latched writers keep; volatile writers match too).
    static TopicQos reader(int depth);
    ~TopicQos();
    TopicQos(TopicQos&& other) noexcept : qos_(other.qos_) { other.qos_ = nullptr; }
    TopicQos(const TopicQos&) = delete;
    TopicQos& operator=(const TopicQos&) = delete;
    const dds_qos_t* get() const { return qos_; }

private:
    explicit TopicQos(int depth);
    dds_qos_t* qos_;
};

// A writer of `type` on ROS 2 topic `ros_name` ("/vkfuse/rig" -> DDS topic
// "rt/vkfuse/rig") in participant.
DdsEntity make_writer(const DdsEntity& participant, const dds_topic_descriptor_t& type, const std::string& ros_name,
                      const TopicQos& qos);

// A reader of `type` on ROS 2 topic `ros_name`.
DdsEntity make_reader(const DdsEntity& participant, const dds_topic_descriptor_t& type, const std::string& ros_name,
                      const TopicQos& qos);

// A wait for a reader's samples: a read condition in a wait set of the
// reader's participant, made once and waited on as often as needed.
class DataWait {
public:
    DataWait(const DdsEntity& participant, const DdsEntity& reader);
    // Whether the reader holds a sample now or one came within `wait`.
    bool wait(std::chrono::nanoseconds wait) const;

private:
    DdsEntity condition_, waitset_;
};

// The reader's next sample, taken on loan and returned when this goes.
template <class Message>
class LoanedSample {
public:
    explicit LoanedSample(const DdsEntity& reader) : reader_(reader.get()) {
        n_ = dds_take(reader_, samples_, &info_, 1, 1);
    }
    ~LoanedSample() {
        if (n_ > 0) dds_return_loan(reader_, samples_, n_);
    }
    LoanedSample(const LoanedSample&) = delete;
    LoanedSample& operator=(const LoanedSample&) = delete;
    bool any() const { return n_ > 0; }                       // a sample, or a notice of a writer's state
    bool valid() const { return n_ > 0 && info_.valid_data; }  // a sample with data
    const Message& message() const { return *static_cast<const Message*>(samples_[0]); }
    const dds_sample_info_t& info() const { return info_; }

private:
    dds_entity_t reader_;
    void* samples_[1] = {nullptr};
    dds_sample_info_t info_{};
    dds_return_t n_ = 0;
};

// Subscribers matched to writer (0 where DDS cannot say).
int matched_subscribers(const DdsEntity& writer);

}  // namespace vkfuse::ros2

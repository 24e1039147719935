// Cyclone DDS entities with an owner, and the QoS ROS 2 gives its topics
// (rmw_cyclonedds_cpp's mapping of rmw_qos_profile_t).
#pragma once
#include <dds/dds.h>

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
    TopicQos() : qos_(dds_create_qos()) {}
    dds_qos_t* qos_;
};

// A writer of `type` on ROS 2 topic `ros_name` ("/vkfuse/rig" -> DDS topic
// "rt/vkfuse/rig") in participant.
DdsEntity make_writer(const DdsEntity& participant, const dds_topic_descriptor_t& type, const std::string& ros_name,
                      const TopicQos& qos);

// A reader of `type` on ROS 2 topic `ros_name`.
DdsEntity make_reader(const DdsEntity& participant, const dds_topic_descriptor_t& type, const std::string& ros_name,
                      const TopicQos& qos);

// Subscribers matched to writer (0 where DDS cannot say).
int matched_subscribers(const DdsEntity& writer);

}  // namespace vkfuse::ros2

#include "ros2/dds_entities.hpp"

#include <cstdlib>

#include "vkfuse/core/error.hpp"
#include "vkfuse/ros2/publisher.hpp"
#include "vkfuse/ros2/remote.hpp"

namespace vkfuse::ros2 {

void check_domain(int domain) {
    if (domain < 0 || domain > kMaxDomain)
        throw Error(ErrorKind::InvalidArgument,
                    "ROS domain " + std::to_string(domain) + ": expected 0.." + std::to_string(kMaxDomain));
}

DdsEntity configured_domain(int domain) {
    check_domain(domain);
    const char* uri = std::getenv("CYCLONEDDS_URI");
    const std::string config = "<General><MaxMessageSize>65500B</MaxMessageSize></General>"
                               "<Internal><SocketReceiveBufferSize max=\"64MB\"/></Internal>," +
                               (uri && *uri ? std::string(uri) + "," : std::string()) +
                               "<Internal><MaxSampleSize>" + std::to_string(kMaxSampleBytes) +
                               "B</MaxSampleSize></Internal>";
    const dds_entity_t d = dds_create_domain(dds_domainid_t(domain), config.c_str());
    return d > 0 ? DdsEntity(d, "DDS domain") : DdsEntity();
}

DdsEntity make_participant(int domain) {
    check_domain(domain);
    return DdsEntity(dds_create_participant(dds_domainid_t(domain), nullptr, nullptr),
                     "DDS participant in domain " + std::to_string(domain));
}

DdsEntity::DdsEntity(dds_entity_t entity, const std::string& what) {
    if (entity < 0) throw Error(ErrorKind::Device, what + ": " + dds_strretcode(entity));
    entity_ = entity;
}

DdsEntity::~DdsEntity() {
    if (entity_ > 0) dds_delete(entity_);
}

DdsEntity& DdsEntity::operator=(DdsEntity&& other) noexcept {
    if (this != &other) {
        if (entity_ > 0) dds_delete(entity_);
        entity_ = other.entity_;
        other.entity_ = 0;
    }
    return *this;
}

TopicQos::TopicQos(int depth, bool latched) : TopicQos(depth) {
    dds_qset_durability(qos_, latched ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
    if (latched)
        dds_qset_durability_service(qos_, 0, DDS_HISTORY_KEEP_LAST, depth, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED,
                                    DDS_LENGTH_UNLIMITED);
    // Samples are never disposed.
    dds_qset_writer_data_lifecycle(qos_, false);
    // Asserted by the participant itself (no call of ours), so a subscriber
    // loses us within the lease however this process ends; a ROS 2
    // subscriber asks for an infinite lease, which this one satisfies.
    dds_qset_liveliness(qos_, DDS_LIVELINESS_AUTOMATIC, DDS_MSECS(kLivelinessLease.count()));
}

// What readers and writers share: reliable, keep last `depth`, plain CDR
// (the only representation ROS 2 readers take).
TopicQos::TopicQos(int depth) : qos_(dds_create_qos()) {
    dds_qset_reliability(qos_, DDS_RELIABILITY_RELIABLE, kMaxBlocking);
    dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, depth);
    const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
    dds_qset_data_representation(qos_, 1, &xcdr1);
}

TopicQos TopicQos::reader(int depth) {
    TopicQos q(depth);
    dds_qset_durability(q.qos_, DDS_DURABILITY_TRANSIENT_LOCAL);
    return q;
}

TopicQos::~TopicQos() {
    if (qos_) dds_delete_qos(qos_);
}

namespace {

// The topic belongs to the participant, which deletes it with its readers and writers.
dds_entity_t topic_of(const DdsEntity& participant, const dds_topic_descriptor_t& type, const std::string& dds_name) {
    const dds_entity_t topic = dds_create_topic(participant.get(), &type, dds_name.c_str(), nullptr, nullptr);
    if (topic < 0) throw Error(ErrorKind::Device, "DDS topic " + dds_name + ": " + dds_strretcode(topic));
    return topic;
}

}  // namespace

DdsEntity make_writer(const DdsEntity& participant, const dds_topic_descriptor_t& type, const std::string& ros_name,
                      const TopicQos& qos) {
    const std::string dds_name = "rt" + ros_name;
    return DdsEntity(dds_create_writer(participant.get(), topic_of(participant, type, dds_name), qos.get(), nullptr),
                     "DDS writer of " + dds_name);
}

DdsEntity make_reader(const DdsEntity& participant, const dds_topic_descriptor_t& type, const std::string& ros_name,
                      const TopicQos& qos) {
    const std::string dds_name = "rt" + ros_name;
    return DdsEntity(dds_create_reader(participant.get(), topic_of(participant, type, dds_name), qos.get(), nullptr),
                     "DDS reader of " + dds_name);
}

DataWait::DataWait(const DdsEntity& participant, const DdsEntity& reader)
    : condition_(dds_create_readcondition(reader.get(), DDS_ANY_STATE), "DDS read condition"),
      waitset_(dds_create_waitset(participant.get()), "DDS wait set") {
    const dds_return_t attached = dds_waitset_attach(waitset_.get(), condition_.get(), 0);
    if (attached < 0) throw Error(ErrorKind::Device, std::string("DDS wait set: ") + dds_strretcode(attached));
}

bool DataWait::wait(std::chrono::nanoseconds wait) const {
    return dds_waitset_wait(waitset_.get(), nullptr, 0, wait.count()) > 0;
}

int matched_subscribers(const DdsEntity& writer) {
    dds_publication_matched_status_t status{};
    return dds_get_publication_matched_status(writer.get(), &status) == DDS_RETCODE_OK ? int(status.current_count) : 0;
}

}  // namespace vkfuse::ros2

#include "fastdds_reader.hpp"

#include <any>
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <map>
#include <stdexcept>

namespace vkfuse::test::ros2 {

using eprosima::fastcdr::Cdr;
namespace dds = eprosima::fastdds::dds;

void Header::read(Cdr& c) { c >> sec >> nanosec >> frame_id; }

void ImageMessage::read(Cdr& c) {
    header.read(c);
    c >> height >> width >> encoding >> is_bigendian >> step >> data;
}

namespace {

// A CDR sequence: its count, then each element as read_one reads it.
template <class T, class ReadOne>
std::vector<T> read_sequence(Cdr& c, ReadOne read_one) {
    std::uint32_t n = 0;
    c >> n;
    std::vector<T> out(n);
    for (T& item : out) read_one(item);
    return out;
}

// Elements Fast-CDR reads itself (a string, a uint8 sequence: a LedSetting).
template <class T>
std::vector<T> read_sequence(Cdr& c) {
    return read_sequence<T>(c, [&](T& item) { c >> item; });
}

}  // namespace

void FusionMetricsMessage::read(Cdr& c) {
    header.read(c);
    c >> serial >> cycle >> status >> error >> method;
    settings = read_sequence<std::vector<std::uint8_t>>(c);
    c >> sharpness >> contrast >> background_diff >> idle >> reused >> watch >> fused_fraction >> changed_fraction >>
        change_score;
}

void RigDescriptionMessage::read(Cdr& c) {
    header.read(c);
    sensors = read_sequence<Sensor>(c, [&](Sensor& s) {
        c >> s.serial >> s.token >> s.model >> s.fps >> s.width >> s.height >> s.led_model;
        s.led_channels = read_sequence<std::string>(c);
        c >> s.led_max_level;
    });
    settings = read_sequence<std::vector<std::uint8_t>>(c);
    c >> method >> fused;
    metrics = read_sequence<std::string>(c);
    c >> skip >> skip_threshold >> background_frames >> frames;
}

void DiagnosticArrayMessage::read(Cdr& c) {
    header.read(c);
    status = read_sequence<Status>(c, [&](Status& s) {
        c >> s.level >> s.name >> s.message >> s.hardware_id;
        s.values = read_sequence<std::pair<std::string, std::string>>(c, [&](auto& kv) { c >> kv.first >> kv.second; });
    });
}

struct Ros2Reader::Impl {
    mutable std::mutex mutex;
    mutable std::condition_variable changed;
    std::map<std::string, std::vector<std::any>> samples;
    int undecodable = 0;
    dds::DomainParticipant* participant = nullptr;
    dds::Subscriber* subscriber = nullptr;
    std::vector<std::unique_ptr<dds::DataReaderListener>> listeners;
};

namespace {

// A message type by its ROS 2 DDS name, received only: no key, no type
// object (as rmw_fastrtps registers them), decoded with M::read.
template <class M>
class ReadOnlyType : public dds::TopicDataType {
public:
    ReadOnlyType() {
        setName(M::kType);
        m_typeSize = 4 << 20;  // a preallocation hint; larger samples reallocate
        m_isGetKeyDefined = false;
        auto_fill_type_object(false);
        auto_fill_type_information(false);
    }
    bool serialize(void*, eprosima::fastrtps::rtps::SerializedPayload_t*) override { return false; }
    bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
        eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char*>(payload->data), payload->length);
        Cdr c(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
        try {
            c.read_encapsulation();
            static_cast<M*>(data)->read(c);
        } catch (const eprosima::fastcdr::exception::Exception&) {
            return false;
        }
        return true;
    }
    std::function<std::uint32_t()> getSerializedSizeProvider(void*) override {
        return [] { return std::uint32_t(0); };
    }
    void* createData() override { return new M(); }
    void deleteData(void* data) override { delete static_cast<M*>(data); }
    bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
};

template <class M>
class Collector : public dds::DataReaderListener {
public:
    Collector(Ros2Reader::Impl& reader, std::string name) : reader_(reader), name_(std::move(name)) {}
    void on_data_available(dds::DataReader* r) override {
        for (;;) {
            M message;
            dds::SampleInfo info;
            const auto rc = r->take_next_sample(&message, &info);
            if (rc != eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
                // take_next_sample reports a sample that failed to decode as an error.
                if (rc != eprosima::fastrtps::types::ReturnCode_t::RETCODE_NO_DATA) {
                    std::lock_guard lock(reader_.mutex);
                    ++reader_.undecodable;
                    reader_.changed.notify_all();
                    continue;
                }
                return;
            }
            if (!info.valid_data) continue;
            std::lock_guard lock(reader_.mutex);
            reader_.samples[name_].push_back(std::move(message));
            reader_.changed.notify_all();
        }
    }

private:
    Ros2Reader::Impl& reader_;
    std::string name_;
};

}  // namespace

Ros2Reader::Ros2Reader(int domain) : impl_(std::make_unique<Impl>()) {
    dds::DomainParticipantQos qos;
    qos.transport().use_builtin_transports = false;
    qos.transport().user_transports.push_back(std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>());
    impl_->participant = dds::DomainParticipantFactory::get_instance()->create_participant(domain, qos);
    if (!impl_->participant) throw std::runtime_error("Fast DDS: no participant in domain " + std::to_string(domain));
    impl_->subscriber = impl_->participant->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
}

Ros2Reader::~Ros2Reader() {
    impl_->participant->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(impl_->participant);
}

template <class M>
void Ros2Reader::subscribe(const std::string& name, bool latched) {
    dds::TypeSupport type(new ReadOnlyType<M>());
    type.register_type(impl_->participant);  // once per type; later calls return an error, harmlessly
    dds::Topic* topic = impl_->participant->create_topic("rt" + name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    if (!topic) throw std::runtime_error("Fast DDS: no topic rt" + name);
    dds::DataReaderQos rq = dds::DATAREADER_QOS_DEFAULT;
    rq.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
    rq.durability().kind = latched ? dds::TRANSIENT_LOCAL_DURABILITY_QOS : dds::VOLATILE_DURABILITY_QOS;
    rq.history().kind = dds::KEEP_ALL_HISTORY_QOS;
    auto& listener = impl_->listeners.emplace_back(std::make_unique<Collector<M>>(*impl_, name));
    if (!impl_->subscriber->create_datareader(topic, rq, listener.get()))
        throw std::runtime_error("Fast DDS: no reader of rt" + name);
}

template <class M>
std::vector<M> Ros2Reader::samples(const std::string& name) const {
    std::lock_guard lock(impl_->mutex);
    std::vector<M> out;
    for (const std::any& a : impl_->samples[name]) out.push_back(std::any_cast<const M&>(a));
    return out;
}

int Ros2Reader::undecodable() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->undecodable;
}

bool Ros2Reader::wait(const std::function<bool()>& done, std::chrono::milliseconds limit) const {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    // `done` reads the samples, which takes the lock: it is called without it.
    while (!done()) {
        if (std::chrono::steady_clock::now() >= deadline) return false;
        std::unique_lock lock(impl_->mutex);
        impl_->changed.wait_for(lock, std::chrono::milliseconds(50));
    }
    return true;
}

#define VKFUSE_ROS2_READER_TYPE(M)                                            \
    template void Ros2Reader::subscribe<M>(const std::string&, bool); \
    template std::vector<M> Ros2Reader::samples<M>(const std::string&) const;
VKFUSE_ROS2_READER_TYPE(ImageMessage)
VKFUSE_ROS2_READER_TYPE(FusionMetricsMessage)
VKFUSE_ROS2_READER_TYPE(RigDescriptionMessage)
VKFUSE_ROS2_READER_TYPE(DiagnosticArrayMessage)

}  // namespace vkfuse::test::ros2

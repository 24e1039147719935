// fastdds_reader.hpp - ROS 2 topics read with Fast DDS, the other DDS
// implementation ROS 2 ships (the default of Humble and Jazzy): what a ROS 2
// node on another host sees of `vkfuse run --publish ros2`, which writes
// through Cyclone DDS. Each message is decoded here from its CDR by hand,
// field by field in ROS 2's order, independently of the IDL vkfuse compiles.
#pragma once
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace eprosima::fastcdr {
class Cdr;
}

namespace vkfuse::test::ros2 {

struct Header {
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
    std::string frame_id;
    void read(eprosima::fastcdr::Cdr& c);
};

struct ImageMessage {  // sensor_msgs/msg/Image
    static constexpr const char* kType = "sensor_msgs::msg::dds_::Image_";
    Header header;
    std::uint32_t height = 0, width = 0;
    std::string encoding;
    std::uint8_t is_bigendian = 0;
    std::uint32_t step = 0;
    std::vector<std::uint8_t> data;
    void read(eprosima::fastcdr::Cdr& c);
};

struct FusionMetricsMessage {  // vkfuse_msgs/msg/FusionMetrics
    static constexpr const char* kType = "vkfuse_msgs::msg::dds_::FusionMetrics_";
    Header header;
    std::string serial;
    std::uint64_t cycle = 0;
    std::uint8_t status = 0;
    std::string error, method;
    std::vector<std::vector<std::uint8_t>> settings;
    double sharpness = 0, contrast = 0, background_diff = 0;
    bool idle = false, reused = false, watch = false;
    double fused_fraction = 0, changed_fraction = 0, change_score = 0;
    void read(eprosima::fastcdr::Cdr& c);
};

struct RigDescriptionMessage {  // vkfuse_msgs/msg/RigDescription
    static constexpr const char* kType = "vkfuse_msgs::msg::dds_::RigDescription_";
    struct Sensor {
        std::string serial, token, model;
        double fps = 0;
        std::uint32_t width = 0, height = 0;
        std::string led_model;
        std::vector<std::string> led_channels;
        std::uint16_t led_max_level = 0;
    };
    Header header;
    std::vector<Sensor> sensors;
    std::vector<std::vector<std::uint8_t>> settings;
    std::string method;
    bool fused = false;
    std::vector<std::string> metrics;
    std::string skip;
    double skip_threshold = 0;
    std::uint32_t background_frames = 0;
    bool frames = false;
    void read(eprosima::fastcdr::Cdr& c);
};

struct DiagnosticArrayMessage {  // diagnostic_msgs/msg/DiagnosticArray
    static constexpr const char* kType = "diagnostic_msgs::msg::dds_::DiagnosticArray_";
    struct Status {
        std::uint8_t level = 0;
        std::string name, message, hardware_id;
        std::vector<std::pair<std::string, std::string>> values;
    };
    Header header;
    std::vector<Status> status;
    void read(eprosima::fastcdr::Cdr& c);
};

// A Fast DDS participant in one domain (UDPv4 only: what reaches another
// host), reading ROS 2 topics with ROS 2's default QoS (reliable; volatile,
// or transient local for a latched topic). Samples arrive on Fast DDS's
// threads and are kept, in order, per topic.
class Ros2Reader {
public:
    explicit Ros2Reader(int domain);
    ~Ros2Reader();
    Ros2Reader(const Ros2Reader&) = delete;
    Ros2Reader& operator=(const Ros2Reader&) = delete;

    // Subscribes to ROS topic `name` ("/vkfuse/rig") of type M.
    template <class M>
    void subscribe(const std::string& name, bool latched = false);
    // The samples of a topic so far, decoded; a sample that failed to decode
    // counts in undecodable().
    template <class M>
    std::vector<M> samples(const std::string& name) const;
    int undecodable() const;
    // Waits (at most `limit`) until `done` holds over the reader's state.
    bool wait(const std::function<bool()>& done, std::chrono::milliseconds limit) const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse::test::ros2

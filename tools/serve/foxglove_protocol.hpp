// serve/foxglove_protocol.hpp - the Foxglove WebSocket protocol (v1: the
// subprotocol foxglove.websocket.v1, and foxglove.sdk.v1, the same wire under
// the Foxglove SDK's name), as far as a server that only publishes speaks it:
//
//   server -> client  text    serverInfo, advertise, status
//   client -> server  text    subscribe {subscriptions: [{id, channelId}]},
//                             unsubscribe {subscriptionIds: [id]}
//   server -> client  binary  0x01 | u32 subscription id | u64 time (ns) | payload
//
// No networking here: what the live server (live_server.cpp) sends and how
// it reads what clients send, checked field by field (a client is hostile
// until its message parses).
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vkfuse::cli::serve {

// The largest client message read; anything longer closes the connection.
inline constexpr std::size_t kMaxClientMessageBytes = 64 * 1024;

// The subprotocol to answer a client's Sec-WebSocket-Protocol offer with
// (a comma-separated list), or nullopt when it offers neither of ours.
std::optional<std::string> choose_subprotocol(std::string_view offered);

struct Channel {
    std::uint32_t id = 0;
    std::string topic;
    std::string encoding;         // "cdr", "json"
    std::string schema_name;      // "sensor_msgs/msg/Image", "vkfuse.Metrics"
    std::string schema;           // its text (ros2msg, jsonschema)
    std::string schema_encoding;  // "ros2msg", "jsonschema"
};

std::string server_info_json(const std::string& name, const std::map<std::string, std::string>& metadata);
std::string advertise_json(const std::vector<Channel>& channels);
enum class StatusLevel { Info = 0, Warning = 1, Error = 2 };
std::string status_json(StatusLevel level, const std::string& message);

// The 13-byte head of a Message Data frame; the payload follows it.
std::string message_data_head(std::uint32_t subscription, std::uint64_t time_ns);

struct Subscription {
    std::uint32_t id = 0, channel = 0;
};
struct ClientRequest {
    enum Op { Subscribe, Unsubscribe } op = Subscribe;
    std::vector<Subscription> subscribe;
    std::vector<std::uint32_t> unsubscribe;
};

// A client's text message as a request; Error(Format) with one line saying
// what is wrong with it ("unknown op \"advertise\" (this server only
// publishes)", "subscriptions[3].channelId: expected an integer in
// 0..4294967295", ...).
ClientRequest parse_client_message(std::string_view text);

// One client's subscriptions: at most one per channel, ids its own.
class Subscriptions {
public:
    // Applies request against the channels that exist; returns one line per
    // entry refused (the rest still apply), as status warnings.
    std::vector<std::string> apply(const ClientRequest& request, const std::vector<Channel>& channels);
    // The subscription of channel, if the client has one.
    std::optional<std::uint32_t> of_channel(std::uint32_t channel) const;
    std::size_t size() const { return by_id_.size(); }

private:
    std::map<std::uint32_t, std::uint32_t> by_id_;       // subscription -> channel
    std::map<std::uint32_t, std::uint32_t> by_channel_;  // channel -> subscription
};

}  // namespace vkfuse::cli::serve

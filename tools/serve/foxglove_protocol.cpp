// The Foxglove WebSocket protocol's messages (foxglove_protocol.hpp).
#include "serve/foxglove_protocol.hpp"

#include <cmath>

#include "io/json_value.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli::serve {
namespace {

constexpr std::string_view kSubprotocols[] = {"foxglove.websocket.v1", "foxglove.sdk.v1"};
// A subscribe message lists at most this many (a flood is refused whole).
constexpr std::size_t kMaxEntries = 4096;

[[noreturn]] void bad(const std::string& why) { throw Error(ErrorKind::Format, why); }

std::uint32_t id_of(const json::Value* v, const std::string& where) {
    if (!v) bad(where + ": missing");
    if (!v->is_number() || v->number() != std::floor(v->number()) || v->number() < 0 || v->number() > 4294967295.0)
        bad(where + ": expected an integer in 0..4294967295");
    return std::uint32_t(v->number());
}

const json::Value::Array& array_of(const json::Value& message, const char* key) {
    const json::Value* v = message.find(key);
    if (!v || !v->is_array()) bad(std::string(key) + ": expected an array");
    if (v->array().size() > kMaxEntries) bad(std::string(key) + ": more than 4096 entries");
    return v->array();
}

}  // namespace

std::optional<std::string> choose_subprotocol(std::string_view offered) {
    while (!offered.empty()) {
        const std::size_t comma = offered.find(',');
        std::string_view item = offered.substr(0, comma);
        offered = comma == std::string_view::npos ? std::string_view() : offered.substr(comma + 1);
        while (!item.empty() && (item.front() == ' ' || item.front() == '\t')) item.remove_prefix(1);
        while (!item.empty() && (item.back() == ' ' || item.back() == '\t')) item.remove_suffix(1);
        for (std::string_view ours : kSubprotocols)
            if (item == ours) return std::string(ours);
    }
    return std::nullopt;
}

std::string server_info_json(const std::string& name, const std::map<std::string, std::string>& metadata) {
    json::Value::Object meta;
    for (const auto& [k, v] : metadata) meta.emplace_back(k, v);
    return json::write(json::Value::Object{
        {"op", "serverInfo"}, {"name", name}, {"capabilities", json::Value::Array{}}, {"metadata", std::move(meta)}});
}

std::string advertise_json(const std::vector<Channel>& channels) {
    json::Value::Array list;
    for (const Channel& c : channels)
        list.push_back(json::Value::Object{{"id", std::uint64_t(c.id)},
                                           {"topic", c.topic},
                                           {"encoding", c.encoding},
                                           {"schemaName", c.schema_name},
                                           {"schema", c.schema},
                                           {"schemaEncoding", c.schema_encoding}});
    return json::write(json::Value::Object{{"op", "advertise"}, {"channels", std::move(list)}});
}

std::string status_json(StatusLevel level, const std::string& message) {
    return json::write(json::Value::Object{{"op", "status"}, {"level", int(level)}, {"message", message}});
}

std::string message_data_head(std::uint32_t subscription, std::uint64_t time_ns) {
    std::string head(13, '\0');
    head[0] = 0x01;
    for (int i = 0; i < 4; ++i) head[std::size_t(1 + i)] = char((subscription >> (8 * i)) & 0xFF);
    for (int i = 0; i < 8; ++i) head[std::size_t(5 + i)] = char((time_ns >> (8 * i)) & 0xFF);
    return head;
}

ClientRequest parse_client_message(std::string_view text) {
    if (text.size() > kMaxClientMessageBytes) bad("a message longer than 64 KiB");
    json::Value message;
    try {
        message = json::parse(text, "message");
    } catch (const Error& e) {
        bad(std::string("not JSON (") + e.what() + ")");
    }
    if (!message.is_object()) bad("expected a JSON object");
    const json::Value* op = message.find("op");
    if (!op || !op->is_string()) bad("op: expected a string");
    ClientRequest r;
    if (op->string() == "subscribe") {
        const auto& list = array_of(message, "subscriptions");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string where = "subscriptions[" + std::to_string(i) + "]";
            if (!list[i].is_object()) bad(where + ": expected an object");
            r.subscribe.push_back({id_of(list[i].find("id"), where + ".id"), id_of(list[i].find("channelId"), where + ".channelId")});
        }
        return r;
    }
    if (op->string() == "unsubscribe") {
        r.op = ClientRequest::Unsubscribe;
        const auto& list = array_of(message, "subscriptionIds");
        for (std::size_t i = 0; i < list.size(); ++i)
            r.unsubscribe.push_back(id_of(&list[i], "subscriptionIds[" + std::to_string(i) + "]"));
        return r;
    }
    bad("op " + json::quote(op->string().substr(0, 40)) +
        " is not supported (this server only publishes: subscribe and unsubscribe)");
}

std::vector<std::string> Subscriptions::apply(const ClientRequest& request, const std::vector<Channel>& channels) {
    std::vector<std::string> refused;
    if (request.op == ClientRequest::Unsubscribe) {
        for (std::uint32_t id : request.unsubscribe) {
            const auto it = by_id_.find(id);
            if (it == by_id_.end()) {
                refused.push_back("unsubscribe: no subscription " + std::to_string(id));
                continue;
            }
            by_channel_.erase(it->second);
            by_id_.erase(it);
        }
        return refused;
    }
    for (const Subscription& s : request.subscribe) {
        const bool exists = s.channel >= 1 && s.channel <= channels.size();
        if (!exists)
            refused.push_back("subscribe: no channel " + std::to_string(s.channel));
        else if (by_id_.count(s.id))
            refused.push_back("subscribe: subscription id " + std::to_string(s.id) + " is in use");
        else if (by_channel_.count(s.channel))
            refused.push_back("subscribe: channel " + std::to_string(s.channel) + " is subscribed already");
        else {
            by_id_[s.id] = s.channel;
            by_channel_[s.channel] = s.id;
        }
    }
    return refused;
}

std::optional<std::uint32_t> Subscriptions::of_channel(std::uint32_t channel) const {
    const auto it = by_channel_.find(channel);
    return it == by_channel_.end() ? std::nullopt : std::optional<std::uint32_t>(it->second);
}

}  // namespace vkfuse::cli::serve

// serve/live_server.hpp - `vkfuse run --serve [ADDR:]PORT`: one port serving
// the live page (its own files only, embedded in the program: no path from a
// request reaches the file system) and a WebSocket speaking the Foxglove
// protocol (foxglove_protocol.hpp) with the channels of live_channels.hpp,
// so the page and Foxglove's own app show the same topics. Built on
// Boost.Beast; the server runs on a thread of its own.
//
// The rig never waits for a client: publish() copies what some client
// subscribed to and hands it over, the newest cycle replacing one not yet
// taken. Each client holds at most one unsent message per channel (a newer
// one replaces it, counted as dropped) and at most kMaxControl queued text
// messages, so a slow or stalled browser costs memory bounded by the
// channels, never the rig's time. Clients are capped (kMaxClients), as are
// the header and message sizes and the time a request may take to arrive.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "serve/live_channels.hpp"
#include "vkfuse/rig/rig.hpp"

namespace vkfuse::cli::serve {

inline constexpr std::size_t kMaxClients = 16;
inline constexpr std::size_t kMaxControl = 64;

struct ServeAddress {
    std::string host = "127.0.0.1";
    std::uint16_t port = 0;  // 0: any free port
};
// "8080", "0.0.0.0:8080", "[::1]:8080": Error(InvalidArgument) naming text otherwise.
ServeAddress parse_serve_address(const std::string& text);

struct ServerCounts {
    std::uint64_t connections = 0;   // WebSocket clients accepted so far
    std::uint64_t sent = 0;          // data messages written to clients
    std::uint64_t dropped = 0;       // replaced by a newer one before a client took it
    std::uint64_t cycles_taken = 0;  // cycles the server encoded
};

class LiveServer {
public:
    // Listens at once; throws Error(InvalidArgument) "--serve ADDR:PORT: cannot listen: ..." when it cannot.
    LiveServer(const ServeAddress& address, LiveChannels channels);
    ~LiveServer();
    LiveServer(const LiveServer&) = delete;
    LiveServer& operator=(const LiveServer&) = delete;

    std::uint16_t port() const;
    // From the rig's loop, each cycle; returns at once.
    void publish(const CycleResult& cycle);
    ServerCounts counts() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkfuse::cli::serve

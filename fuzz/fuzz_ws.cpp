// A WebSocket client's text message through what the live server does with
// it (tools/serve/foxglove_protocol.hpp): parsed into a request, applied to a
// client's subscriptions over a few channels. A request or an Error(Format),
// never a crash, undefined behaviour or a leak; subscriptions never exceed one
// per channel, whatever the message says.
#include <string>
#include <vector>

#include "fuzz_targets.hpp"
#include "vkfuse/core/error.hpp"
#ifdef VKFUSE_WITH_SERVE
#include "serve/foxglove_protocol.hpp"
#endif

namespace vkfuse::fuzz {

int ws(const std::uint8_t* data, std::size_t size) {
#ifdef VKFUSE_WITH_SERVE
    using namespace vkfuse::cli::serve;
    std::vector<Channel> channels(5);
    for (std::uint32_t i = 0; i < channels.size(); ++i) channels[i].id = i + 1;
    Subscriptions subs;
    const std::string text(reinterpret_cast<const char*>(data), size);
    // Twice: the second sees the first one's subscriptions.
    for (int round = 0; round < 2; ++round) {
        try {
            const ClientRequest r = parse_client_message(text);
            subs.apply(r, channels);
        } catch (const Error& e) {
            if (e.kind() != ErrorKind::Format) violated("error kind", e.what());
            if (std::string(e.what()).find('\n') != std::string::npos) violated("error message", e.what());
        }
        if (subs.size() > channels.size()) violated("subscriptions", "more than one per channel");
    }
#else
    (void)data;
    (void)size;
#endif
    return 0;
}

}  // namespace vkfuse::fuzz

VKFUSE_FUZZ_ENTRY(vkfuse::fuzz::ws)

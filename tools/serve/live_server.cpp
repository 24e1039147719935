// The live server on Boost.Beast (live_server.hpp). Everything below runs on
// the server's one thread except publish(), which only copies the cycle and
// posts it.
#include "serve/live_server.hpp"

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "run/run_output.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli::serve {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

struct PageFile {
    const char* path;
    const char* type;
    std::string_view body;
};
// The page's files (tools/serve/page), embedded at build time.
constexpr PageFile kPage[] = {
#include "serve_page.inc"
};

const PageFile* page_file(std::string_view target) {
    if (target == "/") target = "/index.html";
    for (const PageFile& f : kPage)
        if (target == f.path) return &f;
    return nullptr;
}

using Payload = std::shared_ptr<const std::string>;

}  // namespace

class WsSession;

struct LiveServer::Impl {
    net::io_context io{1};
    tcp::acceptor acceptor{io};
    LiveChannels channels;
    std::string name;
    std::thread thread;
    std::unique_ptr<std::atomic<int>[]> subscribers;  // per channel, over every client
    std::vector<Payload> last;                        // per channel: the newest message, for a new subscriber
    std::set<std::shared_ptr<WsSession>> sessions;
    RigStatus status;
    std::mutex mailbox_mutex;
    std::shared_ptr<LiveCycle> mailbox;  // a cycle posted and not yet taken
    std::atomic<std::uint64_t> connections{0}, sent{0}, dropped{0}, cycles_taken{0};

    explicit Impl(LiveChannels c)
        : channels(std::move(c)),
          subscribers(new std::atomic<int>[channels.channels().size()]),
          last(channels.channels().size()),
          status(channels.rig().sensors.size()) {
        for (std::size_t i = 0; i < channels.channels().size(); ++i) subscribers[i] = 0;
        last.back() = std::make_shared<const std::string>(channels.rig_json());  // /vkfuse/rig
    }
    bool wanted(std::uint32_t channel) const { return subscribers[channel - 1] > 0; }
    void accept();
    void take_cycle();
};

namespace {

std::uint64_t ns_of(std::chrono::system_clock::time_point t) {
    return std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count());
}

}  // namespace

// One WebSocket client.
class WsSession : public std::enable_shared_from_this<WsSession> {
public:
    WsSession(tcp::socket&& socket, LiveServer::Impl& server) : ws_(std::move(socket)), server_(server) {}

    void start(http::request<http::string_body> request, std::string subprotocol) {
        ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
        ws_.set_option(websocket::stream_base::decorator([subprotocol](websocket::response_type& res) {
            res.set(http::field::sec_websocket_protocol, subprotocol);
            res.set(http::field::server, "vkfuse");
        }));
        ws_.read_message_max(kMaxClientMessageBytes);
        ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
    }

    // A data message for channel: replaces the one not yet sent.
    void offer(std::uint32_t channel, const Payload& payload, std::uint64_t time_ns) {
        const auto sub = subs_.of_channel(channel);
        if (!sub || !open_) return;
        auto& slot = pending_[channel];
        if (slot.payload) ++server_.dropped;
        slot = {*sub, time_ns, payload};
        write_next();
    }

    void close() {
        if (closed_) return;
        closed_ = true;
        if (open_)
            for (const Channel& c : server_.channels.channels())
                if (subs_.of_channel(c.id)) --server_.subscribers[c.id - 1];
        open_ = false;
        beast::error_code ignored;
        beast::get_lowest_layer(ws_).socket().close(ignored);
        server_.sessions.erase(shared_from_this());
    }

private:
    struct Pending {
        std::uint32_t subscription = 0;
        std::uint64_t time_ns = 0;
        Payload payload;
    };

    void on_accept(beast::error_code ec) {
        if (ec) return close();
        open_ = true;
        ++server_.connections;
        control(server_info_json(server_.name, {{"vkfuse", "live rig"}}));
        control(advertise_json(server_.channels.channels()));
        read();
    }

    void read() {
        ws_.async_read(in_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
    }

    void on_read(beast::error_code ec) {
        if (ec) return close();  // closed, timed out, or a message over the limit
        if (!ws_.got_text()) {
            control(status_json(StatusLevel::Error, "binary messages are not supported (this server only publishes)"));
        } else {
            const std::string text = beast::buffers_to_string(in_.data());
            handle(text);
        }
        in_.consume(in_.size());
        if (open_) read();
    }

    void handle(const std::string& text) {
        ClientRequest request;
        try {
            request = parse_client_message(text);
        } catch (const Error& e) {
            control(status_json(StatusLevel::Error, e.what()));
            return;
        }
        std::set<std::uint32_t> before;
        for (const Channel& c : server_.channels.channels())
            if (subs_.of_channel(c.id)) before.insert(c.id);
        for (const std::string& refused : subs_.apply(request, server_.channels.channels()))
            control(status_json(StatusLevel::Warning, refused));
        for (const Channel& c : server_.channels.channels()) {
            const bool now = subs_.of_channel(c.id).has_value(), was = before.count(c.id) > 0;
            if (now && !was) {
                ++server_.subscribers[c.id - 1];
                if (const Payload& last = server_.last[c.id - 1]) offer(c.id, last, ns_of(std::chrono::system_clock::now()));
            } else if (was && !now) {
                --server_.subscribers[c.id - 1];
                pending_.erase(c.id);
            }
        }
    }

    void control(std::string text) {
        if (!open_) return;
        if (control_.size() >= kMaxControl) return close();  // a client that reads none of its replies
        control_.push_back(std::move(text));
        write_next();
    }

    void write_next() {
        if (writing_ || !open_) return;
        auto done = [self = shared_from_this()](beast::error_code ec, std::size_t) {
            self->writing_ = false;
            if (ec) return self->close();
            self->write_next();
        };
        if (!control_.empty()) {
            writing_ = true;
            out_text_ = std::move(control_.front());
            control_.pop_front();
            ws_.text(true);
            ws_.async_write(net::buffer(out_text_), done);
            return;
        }
        if (pending_.empty()) return;
        // Round robin over channels, so a busy channel does not starve the rest.
        auto it = pending_.upper_bound(last_channel_);
        if (it == pending_.end()) it = pending_.begin();
        last_channel_ = it->first;
        out_data_ = std::move(it->second);
        pending_.erase(it);
        out_head_ = message_data_head(out_data_.subscription, out_data_.time_ns);
        writing_ = true;
        ++server_.sent;
        ws_.binary(true);
        ws_.async_write(std::array<net::const_buffer, 2>{net::buffer(out_head_), net::buffer(*out_data_.payload)}, done);
    }

    websocket::stream<beast::tcp_stream> ws_;
    LiveServer::Impl& server_;
    beast::flat_buffer in_;
    Subscriptions subs_;
    std::deque<std::string> control_;
    std::map<std::uint32_t, Pending> pending_;  // by channel
    std::uint32_t last_channel_ = 0;
    std::string out_text_, out_head_;
    Pending out_data_;
    bool writing_ = false, open_ = false, closed_ = false;
};

namespace {

// One HTTP connection: the page's files, or the upgrade to a WebSocket.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
public:
    HttpSession(tcp::socket&& socket, LiveServer::Impl& server) : stream_(std::move(socket)), server_(server) {}

    void read() {
        parser_.emplace();
        parser_->header_limit(8 * 1024);
        parser_->body_limit(8 * 1024);
        // A client that trickles its request (slowloris) is cut off.
        stream_.expires_after(std::chrono::seconds(10));
        http::async_read(stream_, buffer_, *parser_,
                         [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
    }

private:
    void on_read(beast::error_code ec) {
        if (ec) return shut();
        http::request<http::string_body> req = parser_->release();
        if (websocket::is_upgrade(req)) return upgrade(std::move(req));
        if (req.method() != http::verb::get && req.method() != http::verb::head)
            return respond(req, http::status::method_not_allowed, "text/plain", "only GET\n");
        const PageFile* file = page_file(req.target());
        if (!file) return respond(req, http::status::not_found, "text/plain", "not found\n");
        respond(req, http::status::ok, file->type, std::string(file->body));
    }

    void upgrade(http::request<http::string_body> req) {
        const auto offered = choose_subprotocol(req[http::field::sec_websocket_protocol]);
        if (req.target() != "/" || !offered)
            return respond(req, http::status::bad_request, "text/plain",
                           "a WebSocket here speaks foxglove.websocket.v1 (or foxglove.sdk.v1) at /\n");
        if (server_.sessions.size() >= kMaxClients)
            return respond(req, http::status::service_unavailable, "text/plain", "too many clients\n");
        stream_.expires_never();
        auto session = std::make_shared<WsSession>(stream_.release_socket(), server_);
        server_.sessions.insert(session);
        session->start(std::move(req), *offered);
    }

    void respond(const http::request<http::string_body>& req, http::status status, const char* type, std::string body) {
        auto res = std::make_shared<http::response<http::string_body>>(status, req.version());
        res->set(http::field::server, "vkfuse");
        res->set(http::field::content_type, type);
        res->set(http::field::cache_control, "no-store");
        res->keep_alive(req.keep_alive() && status == http::status::ok);
        res->body() = req.method() == http::verb::head ? std::string() : std::move(body);
        res->prepare_payload();
        if (req.method() == http::verb::head) res->content_length(body.size());
        http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code ec, std::size_t) {
            if (ec || !res->keep_alive()) return self->shut();
            self->read();
        });
    }

    void shut() {
        beast::error_code ignored;
        stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    }

    beast::tcp_stream stream_;
    LiveServer::Impl& server_;
    beast::flat_buffer buffer_;
    std::optional<http::request_parser<http::string_body>> parser_;
};

}  // namespace

void LiveServer::Impl::accept() {
    acceptor.async_accept(io, [self = this](beast::error_code ec, tcp::socket socket) {
        if (!ec) std::make_shared<HttpSession>(std::move(socket), *self)->read();
        if (self->acceptor.is_open()) self->accept();
    });
}

void LiveServer::Impl::take_cycle() {
    std::shared_ptr<LiveCycle> cycle;
    {
        std::lock_guard lock(mailbox_mutex);
        cycle = std::move(mailbox);
    }
    if (!cycle) return;
    ++cycles_taken;
    status.add(*cycle);
    const std::uint64_t t = ns_of(cycle->at);
    for (const Channel& c : channels.channels()) {
        const ChannelRole& role = channels.role(c.id);
        Payload payload;
        if (role.kind == ChannelRole::Status) {
            payload = std::make_shared<const std::string>(status.json());
        } else if (role.kind != ChannelRole::Rig && wanted(c.id)) {
            const LiveCycle::Sensor& s = cycle->sensors[role.sensor];
            const std::string& serial = s.serial;
            if (role.kind == ChannelRole::Metrics && !s.metrics_line.empty())
                payload = std::make_shared<const std::string>(s.metrics_line);
            else if (role.kind == ChannelRole::Fused && s.fused.size() > 0)
                payload = std::make_shared<const std::string>(image_cdr(serial, cycle->at, s.fused));
            else if (role.kind == ChannelRole::FusedPng && s.fused.size() > 0)
                payload = std::make_shared<const std::string>(png_cdr(serial, cycle->at, s.fused));
            else if (role.kind == ChannelRole::Lit && role.slot < s.lit.size() && !s.lit[role.slot].empty())
                payload = std::make_shared<const std::string>(
                    image_cdr(serial, cycle->at, s.height, s.width, s.lit[role.slot].data()));
            else if (role.kind == ChannelRole::LitJpeg && role.slot < s.lit.size() && !s.lit[role.slot].empty())
                payload = std::make_shared<const std::string>(
                    jpeg_cdr(serial, cycle->at, s.height, s.width, s.lit[role.slot].data()));
        }
        if (!payload) continue;
        last[c.id - 1] = payload;
        for (const auto& session : std::vector<std::shared_ptr<WsSession>>(sessions.begin(), sessions.end()))
            session->offer(c.id, payload, t);
    }
}

ServeAddress parse_serve_address(const std::string& text) {
    ServeAddress a;
    std::string port = text;
    if (const auto colon = text.rfind(':'); colon != std::string::npos) {
        a.host = text.substr(0, colon);
        port = text.substr(colon + 1);
        if (a.host.size() >= 2 && a.host.front() == '[' && a.host.back() == ']') a.host = a.host.substr(1, a.host.size() - 2);
    }
    beast::error_code ec;
    net::ip::make_address(a.host, ec);
    if (ec || a.host.empty())
        throw Error(ErrorKind::InvalidArgument, "--serve " + text + ": expected [ADDR:]PORT with ADDR an IP address");
    if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos || std::stoi(port) > 65535)
        throw Error(ErrorKind::InvalidArgument, "--serve " + text + ": expected a port in 0..65535");
    a.port = std::uint16_t(std::stoi(port));
    return a;
}

LiveServer::LiveServer(const ServeAddress& address, LiveChannels channels) : impl_(std::make_unique<Impl>(std::move(channels))) {
    impl_->name = "vkfuse run";
    const std::string about = "--serve " + address.host + ":" + std::to_string(address.port);
    beast::error_code ec;
    const tcp::endpoint endpoint(net::ip::make_address(address.host), address.port);
    impl_->acceptor.open(endpoint.protocol(), ec);
    if (!ec) impl_->acceptor.set_option(net::socket_base::reuse_address(true), ec);
    if (!ec) impl_->acceptor.bind(endpoint, ec);
    if (!ec) impl_->acceptor.listen(net::socket_base::max_listen_connections, ec);
    if (ec) throw Error(ErrorKind::InvalidArgument, about + ": cannot listen: " + ec.message());
    impl_->accept();
    impl_->thread = std::thread([impl = impl_.get()] {
        // The rig's threads come first: a page is worth less than a cycle.
        ::setpriority(PRIO_PROCESS, pid_t(::syscall(SYS_gettid)), 5);
        impl->io.run();
    });
}

// Handlers hold the sessions, never the server: what is still pending when
// the thread stops is destroyed with the io_context, sockets closed.
LiveServer::~LiveServer() {
    net::post(impl_->io, [impl = impl_.get()] {
        beast::error_code ignored;
        impl->acceptor.close(ignored);
        for (const auto& s : std::vector<std::shared_ptr<WsSession>>(impl->sessions.begin(), impl->sessions.end())) s->close();
        impl->io.stop();
    });
    impl_->thread.join();
}

std::uint16_t LiveServer::port() const { return impl_->acceptor.local_endpoint().port(); }

ServerCounts LiveServer::counts() const {
    return {impl_->connections, impl_->sent, impl_->dropped, impl_->cycles_taken};
}

void LiveServer::publish(const CycleResult& cycle) {
    Impl& s = *impl_;
    const LiveChannels& ch = s.channels;
    // What some client subscribed to, by sensor: only that is copied.
    const std::size_t settings = ch.rig().sequence.size();
    std::vector<char> metrics(cycle.sensors.size()), fused(cycle.sensors.size()), lit(cycle.sensors.size() * settings);
    for (const Channel& c : ch.channels()) {
        const ChannelRole& role = ch.role(c.id);
        if (!s.wanted(c.id) || role.sensor >= cycle.sensors.size()) continue;
        if (role.kind == ChannelRole::Metrics) metrics[role.sensor] = 1;
        if (role.kind == ChannelRole::Fused || role.kind == ChannelRole::FusedPng) fused[role.sensor] = 1;
        if (role.kind == ChannelRole::Lit || role.kind == ChannelRole::LitJpeg) lit[role.sensor * settings + role.slot] = 1;
    }
    auto live = std::make_shared<LiveCycle>();
    live->cycle = cycle.cycle;
    live->at = std::chrono::system_clock::now();
    live->capture_wait_s = cycle.capture_wait_s;
    live->fuse_s = cycle.fuse_s;
    for (std::size_t i = 0; i < cycle.sensors.size(); ++i) {
        const SensorCycle& c = cycle.sensors[i];
        LiveCycle::Sensor out;
        out.serial = c.serial;
        out.status = c.status;
        out.error = c.error;
        out.idle = c.skip.idle;
        out.reused = c.skip.reused;
        out.watch = c.watch;
        out.fused_fraction = c.skip.fused_fraction;
        if (metrics[i]) out.metrics_line = metrics_line(cycle, c, ch.rig().object, ch.rig().skipping);
        if (c.status == SensorStatus::Ok) {
            if (c.fused && fused[i]) out.fused = *c.fused;  // rounded and encoded on the server's thread
            out.lit.resize(settings);
            for (std::size_t k = 0; k < c.frames.size() && k < settings; ++k)
                if (lit[i * settings + k]) {
                    out.lit[k] = c.frames[k].pixels;
                    out.height = c.frames[k].height;
                    out.width = c.frames[k].width;
                }
        }
        live->sensors.push_back(std::move(out));
    }
    bool post = false;
    {
        std::lock_guard lock(s.mailbox_mutex);
        post = !s.mailbox;
        s.mailbox = std::move(live);  // the newest replaces one not yet taken
    }
    if (post) net::post(s.io, [impl = impl_.get()] { impl->take_cycle(); });
}

}  // namespace vkfuse::cli::serve

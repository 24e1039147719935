// The live server's protocol layer (tools/serve): the Foxglove messages it
// writes, what it makes of clients' messages (hostile ones included), the
// subscriptions it keeps, its images in ROS 2's CDR and the address option.
// tests/serve/check_live.py drives the whole server with real clients.
#ifdef VKFUSE_WITH_SERVE
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "expect_error.hpp"
#include "io/cdr.hpp"
#include "io/json_value.hpp"
#include "io/png.hpp"
#include "sensor/frame_codec.hpp"
#include "serve/foxglove_protocol.hpp"
#include "serve/live_channels.hpp"
#include "serve/live_server.hpp"

namespace vkfuse::test {
namespace {

using namespace vkfuse::cli::serve;

TEST(ServeProtocol, TheSubprotocolIsOneOfFoxglovesNames) {
    EXPECT_EQ(choose_subprotocol("foxglove.websocket.v1"), "foxglove.websocket.v1");
    EXPECT_EQ(choose_subprotocol("x, foxglove.sdk.v1 ,y"), "foxglove.sdk.v1");
    EXPECT_EQ(choose_subprotocol(""), std::nullopt);
    EXPECT_EQ(choose_subprotocol("foxglove.websocket.v10"), std::nullopt);
}

TEST(ServeProtocol, MessageDataHeadIsOpcodeSubscriptionAndTime) {
    const std::string h = message_data_head(0x01020304u, 0x1122334455667788ull);
    ASSERT_EQ(h.size(), 13u);
    EXPECT_EQ(std::uint8_t(h[0]), 1);
    EXPECT_EQ(std::uint8_t(h[1]), 0x04);
    EXPECT_EQ(std::uint8_t(h[4]), 0x01);
    EXPECT_EQ(std::uint8_t(h[5]), 0x88);
    EXPECT_EQ(std::uint8_t(h[12]), 0x11);
}

TEST(ServeProtocol, ClientMessagesParseOrSayWhatIsWrong) {
    const ClientRequest sub = parse_client_message(R"({"op": "subscribe", "subscriptions": [{"id": 7, "channelId": 3}]})");
    ASSERT_EQ(sub.op, ClientRequest::Subscribe);
    ASSERT_EQ(sub.subscribe.size(), 1u);
    EXPECT_EQ(sub.subscribe[0].id, 7u);
    EXPECT_EQ(sub.subscribe[0].channel, 3u);
    const ClientRequest unsub = parse_client_message(R"({"op": "unsubscribe", "subscriptionIds": [7, 8]})");
    EXPECT_EQ(unsub.op, ClientRequest::Unsubscribe);
    EXPECT_EQ(unsub.unsubscribe.size(), 2u);
    const struct {
        const char* text;
        const char* fragment;
    } bad[] = {
        {"", "not JSON"},
        {"{", "not JSON"},
        {"[]", "expected a JSON object"},
        {R"({"op": 3})", "op: expected a string"},
        {R"({"op": "setParameters"})", "op \"setParameters\" is not supported"},
        {R"({"op": "subscribe"})", "subscriptions: expected an array"},
        {R"({"op": "subscribe", "subscriptions": [5]})", "subscriptions[0]: expected an object"},
        {R"({"op": "subscribe", "subscriptions": [{"id": 1.5, "channelId": 1}]})", "subscriptions[0].id"},
        {R"({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 4294967296}]})", "subscriptions[0].channelId"},
        {R"({"op": "subscribe", "subscriptions": [{"id": 1}]})", "subscriptions[0].channelId: missing"},
        {R"({"op": "unsubscribe", "subscriptionIds": ["a"]})", "subscriptionIds[0]"},
    };
    for (const auto& b : bad) {
        SCOPED_TRACE(b.text);
        try {
            parse_client_message(b.text);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Format);
            EXPECT_NE(std::string(e.what()).find(b.fragment), std::string::npos) << e.what();
        }
    }
    std::string flood = R"({"op": "subscribe", "subscriptions": [)";
    for (int i = 0; i < 5000; ++i) flood += std::string(i ? "," : "") + "{}";
    EXPECT_THROW(parse_client_message(flood + "]}"), Error);
    EXPECT_THROW(parse_client_message(std::string(kMaxClientMessageBytes + 1, ' ')), Error);
}

TEST(ServeProtocol, SubscriptionsAreOnePerChannelWithIdsOfTheClients) {
    std::vector<Channel> channels(3);
    for (std::uint32_t i = 0; i < 3; ++i) channels[i].id = i + 1;
    Subscriptions subs;
    ClientRequest r;
    r.subscribe = {{10, 1}, {11, 2}, {10, 3}, {12, 2}, {13, 9}};
    const auto refused = subs.apply(r, channels);
    ASSERT_EQ(refused.size(), 3u);
    EXPECT_NE(refused[0].find("subscription id 10 is in use"), std::string::npos);
    EXPECT_NE(refused[1].find("channel 2 is subscribed already"), std::string::npos);
    EXPECT_NE(refused[2].find("no channel 9"), std::string::npos);
    EXPECT_EQ(subs.of_channel(1), 10u);
    EXPECT_EQ(subs.of_channel(2), 11u);
    EXPECT_EQ(subs.of_channel(3), std::nullopt);
    ClientRequest u;
    u.op = ClientRequest::Unsubscribe;
    u.unsubscribe = {10, 99};
    EXPECT_EQ(subs.apply(u, channels).size(), 1u);
    EXPECT_EQ(subs.of_channel(1), std::nullopt);
    EXPECT_EQ(subs.size(), 1u);
}

TEST(ServeChannels, EverySensorHasFusedLitAndMetricsThenStatusAndRig) {
    LiveRig rig;
    rig.sensors = {{"DIGIT", "D2-01", 4, 2, 30, LedLayout::digit()}, {"DIGIT", "7up", 4, 2, 30, LedLayout::digit()}};
    rig.sequence = parse_sequence("15,15,15+0,15,0");
    rig.method = "wavelet/bior4.4";
    rig.static_slot = 0;
    const LiveChannels live(rig);
    std::vector<std::string> topics;
    for (const Channel& c : live.channels()) topics.push_back(c.topic);
    EXPECT_EQ(topics, (std::vector<std::string>{
                          "/vkfuse/D2_01/fused", "/vkfuse/D2_01/fused/compressed", "/vkfuse/D2_01/lit/led_15_15_15",
                          "/vkfuse/D2_01/lit/led_0_15_0", "/vkfuse/D2_01/lit/led_15_15_15/compressed",
                          "/vkfuse/D2_01/lit/led_0_15_0/compressed", "/vkfuse/D2_01/metrics",
                          "/vkfuse/sensor_7up/fused", "/vkfuse/sensor_7up/fused/compressed",
                          "/vkfuse/sensor_7up/lit/led_15_15_15", "/vkfuse/sensor_7up/lit/led_0_15_0",
                          "/vkfuse/sensor_7up/lit/led_15_15_15/compressed",
                          "/vkfuse/sensor_7up/lit/led_0_15_0/compressed", "/vkfuse/sensor_7up/metrics",
                          "/vkfuse/status", "/vkfuse/rig"}));
    EXPECT_EQ(live.role(2).kind, ChannelRole::FusedPng);
    EXPECT_EQ(live.role(4).kind, ChannelRole::Lit);
    EXPECT_EQ(live.role(4).slot, 1u);
    EXPECT_EQ(live.role(6).kind, ChannelRole::LitJpeg);
    EXPECT_EQ(live.role(6).slot, 1u);
    EXPECT_EQ(live.role(14).sensor, 1u);
    EXPECT_EQ(live.role(14).kind, ChannelRole::Metrics);
    const json::Value description = json::parse(live.rig_json(), "rig");
    EXPECT_EQ(description.find("sensors")->array()[1].find("token")->string(), "sensor_7up");
    // Advertised as Foxglove expects: every field, schemas as text.
    const json::Value advertise = json::parse(advertise_json(live.channels()), "advertise");
    const json::Value& first = advertise.find("channels")->array()[0];
    EXPECT_EQ(first.find("schemaName")->string(), "sensor_msgs/msg/Image");
    EXPECT_EQ(first.find("schemaEncoding")->string(), "ros2msg");
    EXPECT_NE(first.find("schema")->string().find("MSG: builtin_interfaces/Time"), std::string::npos);
}

TEST(ServeChannels, ImagesAreRos2ImagesInCdr) {
    const std::uint8_t rgb[2 * 3 * 3] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18};
    const auto at = std::chrono::system_clock::time_point(std::chrono::nanoseconds(1'700'000'000'123'456'789ll));
    const std::string cdr = image_cdr("SIM-0001", at, 2, 3, rgb);
    io::cdr::Reader r(cdr);
    EXPECT_EQ(r.num<std::int32_t>(), 1'700'000'000);
    EXPECT_EQ(r.num<std::uint32_t>(), 123'456'789u);
    EXPECT_EQ(r.str(), "SIM-0001");
    EXPECT_EQ(r.num<std::uint32_t>(), 2u);
    EXPECT_EQ(r.num<std::uint32_t>(), 3u);
    EXPECT_EQ(r.str(), "rgb8");
    EXPECT_EQ(r.num<std::uint8_t>(), 0u);
    EXPECT_EQ(r.num<std::uint32_t>(), 9u);
    EXPECT_EQ(r.octets(), std::string_view(reinterpret_cast<const char*>(rgb), sizeof rgb));
    EXPECT_FALSE(r.failed());
}

TEST(ServeChannels, TheFusedPngIsTheOutPngByteForByte) {
    Image fused(3, 5, 3);
    for (std::size_t i = 0; i < fused.data.size(); ++i) fused.data[i] = float(i) / 40.0f - 0.1f;  // clamped at both ends
    const std::string cdr = png_cdr("S", std::chrono::system_clock::time_point{}, fused);
    io::cdr::Reader r(cdr);
    r.num<std::int32_t>();
    r.num<std::uint32_t>();
    r.str();
    EXPECT_EQ(r.str(), "png");
    const std::string_view png = r.octets();
    const Image back = io::decode_png(std::vector<unsigned char>(png.begin(), png.end()), "S");
    const std::vector<unsigned char> want = io::to_8bit(fused);
    ASSERT_EQ(back.data.size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(std::lround(back.data[i] * 255.0f), want[i]) << i;
}

TEST(ServeChannels, CompressedImagesAreJpegsOfTheFrame) {
    std::vector<std::uint8_t> rgb(16 * 8 * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::uint8_t(i * 7);
    const std::string cdr = jpeg_cdr("S", std::chrono::system_clock::time_point{}, 8, 16, rgb.data());
    io::cdr::Reader r(cdr);
    r.num<std::int32_t>();
    r.num<std::uint32_t>();
    EXPECT_EQ(r.str(), "S");
    EXPECT_EQ(r.str(), "jpeg");
    const std::string_view jpeg = r.octets();
    EXPECT_FALSE(r.failed());
    ASSERT_GT(jpeg.size(), 4u);
    EXPECT_EQ(std::uint8_t(jpeg[0]), 0xFF);  // SOI
    EXPECT_EQ(std::uint8_t(jpeg[1]), 0xD8);
    std::vector<std::uint8_t> back;
    std::string why;
    EXPECT_TRUE(mjpeg_to_rgb({reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size()}, 16, 8, back, why)) << why;
}

TEST(ServeAddressOption, PortOrAddressAndPort) {
    EXPECT_EQ(parse_serve_address("8080").host, "127.0.0.1");
    EXPECT_EQ(parse_serve_address("8080").port, 8080);
    EXPECT_EQ(parse_serve_address("0.0.0.0:0").host, "0.0.0.0");
    EXPECT_EQ(parse_serve_address("[::1]:9").host, "::1");
    for (const char* bad : {"", "65536", "localhost:80", "1.2.3.4:", "80x", ":80", "1.2.3.4:-1"}) {
        SCOPED_TRACE(bad);
        expect_error([&] { parse_serve_address(bad); }, std::string("--serve ") + bad, ErrorKind::InvalidArgument, "");
    }
}

}  // namespace
}  // namespace vkfuse::test
#endif

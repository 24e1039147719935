// Building the --json output one member at a time.
#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace vkfuse::bench {

// A JSON object under construction; members keep the order they are added in.
class JsonObject {
public:
    JsonObject& number(std::string_view key, double value);  // non-finite -> null
    JsonObject& number_or_null(std::string_view key, std::optional<double> value);
    JsonObject& integer(std::string_view key, long long value);
    JsonObject& text(std::string_view key, std::string_view value);
    JsonObject& text_or_null(std::string_view key, const std::optional<std::string>& value);
    JsonObject& boolean(std::string_view key, bool value);
    JsonObject& null(std::string_view key);
    JsonObject& raw(std::string_view key, const std::string& json);  // an already encoded value
    std::string str() const { return "{" + body_ + "}"; }

private:
    std::string body_;
    JsonObject& member(std::string_view key, const std::string& json);
};

}  // namespace vkfuse::bench

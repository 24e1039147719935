#include "json_writer.hpp"

#include "json.hpp"  // tools/: the CLI's string escaping and number format

namespace vkfuse::bench {

JsonObject& JsonObject::member(std::string_view key, const std::string& json) {
    if (!body_.empty()) body_ += ", ";
    body_ += cli::json_string(key) + ": " + json;
    return *this;
}

JsonObject& JsonObject::number(std::string_view key, double value) { return member(key, cli::json_number(value)); }

JsonObject& JsonObject::number_or_null(std::string_view key, std::optional<double> value) {
    return value ? number(key, *value) : null(key);
}

JsonObject& JsonObject::integer(std::string_view key, long long value) { return member(key, std::to_string(value)); }

JsonObject& JsonObject::text(std::string_view key, std::string_view value) { return member(key, cli::json_string(value)); }

JsonObject& JsonObject::text_or_null(std::string_view key, const std::optional<std::string>& value) {
    return value ? text(key, *value) : null(key);
}

JsonObject& JsonObject::boolean(std::string_view key, bool value) { return member(key, value ? "true" : "false"); }

JsonObject& JsonObject::null(std::string_view key) { return member(key, "null"); }

JsonObject& JsonObject::raw(std::string_view key, const std::string& json) { return member(key, json); }

}  // namespace vkfuse::bench

// A small JSON reader: enough for the peers' one-object answers and for
// checking the benchmark's own --json output, without a dependency.
#pragma once
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vkfuse::bench {

struct JsonValue {
    enum class Type { Null, Bool, Number, String, Array, Object };
    Type type = Type::Null;
    bool boolean = false;
    double number = 0;
    std::string string;
    std::vector<JsonValue> array;
    std::vector<std::pair<std::string, JsonValue>> object;  // in document order

    // The member named key of an object, or nullptr.
    const JsonValue* find(std::string_view key) const;
};

// Parses one JSON document (RFC 8259; \u escapes outside ASCII become UTF-8).
// Throws std::runtime_error "JSON: <problem> at offset N".
JsonValue parse_json(std::string_view text);

}  // namespace vkfuse::bench

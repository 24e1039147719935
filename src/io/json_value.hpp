// io/json_value.hpp - a small JSON model (dataset manifests, CLI output):
// parse (strict RFC 8259, errors with line numbers) and write (keys in order).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace vkfuse::json {

class Value {
public:
    using Array = std::vector<Value>;
    using Object = std::vector<std::pair<std::string, Value>>;  // insertion order, as written

    Value() = default;
    Value(std::nullptr_t) {}
    Value(bool b) : v_(b) {}
    Value(double d) : v_(d) {}
    Value(int i) : v_(double(i)) {}
    Value(std::uint64_t u) : v_(double(u)) {}
    Value(std::int64_t i) : v_(double(i)) {}
    Value(std::string s) : v_(std::move(s)) {}
    Value(const char* s) : v_(std::string(s)) {}
    Value(Array a) : v_(std::move(a)) {}
    Value(Object o) : v_(std::move(o)) {}

    bool is_null() const { return std::holds_alternative<std::nullptr_t>(v_); }
    bool is_bool() const { return std::holds_alternative<bool>(v_); }
    bool is_number() const { return std::holds_alternative<double>(v_); }
    bool is_string() const { return std::holds_alternative<std::string>(v_); }
    bool is_array() const { return std::holds_alternative<Array>(v_); }
    bool is_object() const { return std::holds_alternative<Object>(v_); }

    // Unchecked accessors: call the matching is_*() first (the manifest reader does).
    bool boolean() const { return std::get<bool>(v_); }
    double number() const { return std::get<double>(v_); }
    const std::string& string() const { return std::get<std::string>(v_); }
    const Array& array() const { return std::get<Array>(v_); }
    const Object& object() const { return std::get<Object>(v_); }

    // The member named key of an object, or nullptr (also when this is no object).
    const Value* find(std::string_view key) const;

private:
    std::variant<std::nullptr_t, bool, double, std::string, Array, Object> v_;
};

// Throws Error(Format) "<source>: line L: <problem>" on anything that is not one JSON value.
Value parse(std::string_view text, const std::string& source);

// text as a JSON string: quotes, '"' and '\' escaped, control characters as
// \uXXXX; well-formed UTF-8 passes through, and every byte that is not part
// of a well-formed sequence (a Latin-1 file name, a cut-off character) is
// written as \ufffd, so the result is always valid JSON (and valid UTF-8).
// That is lossy by design: such a name cannot be spelled in JSON at all.
std::string quote(std::string_view text);

// Two-space indentation; an array or object holding only scalars stays on one
// line, so a manifest lists one frame per line. Numbers round-trip (%.17g,
// integers without exponent); NaN/Inf, which JSON lacks, become null.
std::string write(const Value& value);

}  // namespace vkfuse::json

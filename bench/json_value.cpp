#include "json_value.hpp"

#include <cstdlib>
#include <stdexcept>

namespace vkfuse::bench {
namespace {

class Parser {
public:
    explicit Parser(std::string_view text) : text_(text) {}

    JsonValue document() {
        JsonValue v = value();
        skip_space();
        if (pos_ != text_.size()) fail("trailing characters");
        return v;
    }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    int depth_ = 0;

    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(pos_));
    }
    void skip_space() {
        while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\n' || text_[pos_] == '\r'))
            ++pos_;
    }
    char peek() {
        skip_space();
        if (pos_ >= text_.size()) fail("unexpected end");
        return text_[pos_];
    }
    void expect(char c) {
        if (peek() != c) fail(std::string("expected '") + c + "'");
        ++pos_;
    }
    bool literal(std::string_view word) {
        if (text_.substr(pos_, word.size()) != word) return false;
        pos_ += word.size();
        return true;
    }

    JsonValue value() {
        if (++depth_ > 64) fail("nesting too deep");
        JsonValue v;
        const char c = peek();
        if (c == '{') {
            v = object();
        } else if (c == '[') {
            v = array();
        } else if (c == '"') {
            v.type = JsonValue::Type::String;
            v.string = string();
        } else if (literal("true")) {
            v.type = JsonValue::Type::Bool;
            v.boolean = true;
        } else if (literal("false")) {
            v.type = JsonValue::Type::Bool;
        } else if (literal("null")) {
            v.type = JsonValue::Type::Null;
        } else {
            v.type = JsonValue::Type::Number;
            v.number = number();
        }
        --depth_;
        return v;
    }

    JsonValue object() {
        JsonValue v;
        v.type = JsonValue::Type::Object;
        expect('{');
        if (peek() == '}') return ++pos_, v;
        while (true) {
            if (peek() != '"') fail("expected a member name");
            std::string key = string();
            expect(':');
            v.object.emplace_back(std::move(key), value());
            if (peek() == '}') return ++pos_, v;
            expect(',');
        }
    }

    JsonValue array() {
        JsonValue v;
        v.type = JsonValue::Type::Array;
        expect('[');
        if (peek() == ']') return ++pos_, v;
        while (true) {
            v.array.push_back(value());
            if (peek() == ']') return ++pos_, v;
            expect(',');
        }
    }

    double number() {
        const std::size_t start = pos_;
        while (pos_ < text_.size() && std::string_view("+-0123456789.eE").find(text_[pos_]) != std::string_view::npos) ++pos_;
        const std::string token(text_.substr(start, pos_ - start));
        char* end = nullptr;
        const double d = token.empty() ? 0 : std::strtod(token.c_str(), &end);
        if (token.empty() || end != token.c_str() + token.size()) fail("bad value");
        return d;
    }

    void append_utf8(std::string& out, unsigned cp) {
        if (cp < 0x80) {
            out += char(cp);
        } else if (cp < 0x800) {
            out += char(0xC0 | (cp >> 6));
            out += char(0x80 | (cp & 0x3F));
        } else {
            out += char(0xE0 | (cp >> 12));
            out += char(0x80 | ((cp >> 6) & 0x3F));
            out += char(0x80 | (cp & 0x3F));
        }
    }

    std::string string() {
        expect('"');
        std::string out;
        while (true) {
            if (pos_ >= text_.size()) fail("unterminated string");
            const char c = text_[pos_++];
            if (c == '"') return out;
            if (c != '\\') {
                out += c;
                continue;
            }
            if (pos_ >= text_.size()) fail("unterminated string");
            const char e = text_[pos_++];
            switch (e) {
                case 'n': out += '\n'; break;
                case 't': out += '\t'; break;
                case 'r': out += '\r'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'u': {
                    if (pos_ + 4 > text_.size()) fail("bad \\u escape");
                    const std::string hex(text_.substr(pos_, 4));
                    pos_ += 4;
                    append_utf8(out, unsigned(std::strtoul(hex.c_str(), nullptr, 16)));
                    break;
                }
                default: out += e;  // \" \\ \/
            }
        }
    }
};

}  // namespace

const JsonValue* JsonValue::find(std::string_view key) const {
    for (const auto& [k, v] : object)
        if (k == key) return &v;
    return nullptr;
}

JsonValue parse_json(std::string_view text) { return Parser(text).document(); }

}  // namespace vkfuse::bench

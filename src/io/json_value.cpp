#include "io/json_value.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "vkfuse/core/error.hpp"

namespace vkfuse::json {
namespace {

// Recursive descent over the whole text; depth is bounded so a hostile file
// cannot overflow the stack.
class Parser {
public:
    Parser(std::string_view text, const std::string& source) : text_(text), source_(source) {}

    Value document() {
        Value v = value(0);
        skip_space();
        if (pos_ != text_.size()) fail("unexpected text after the JSON value");
        return v;
    }

private:
    static constexpr int kMaxDepth = 64;
    std::string_view text_;
    const std::string& source_;
    std::size_t pos_ = 0;

    [[noreturn]] void fail(const std::string& problem) const {
        int line = 1;
        for (std::size_t i = 0; i < pos_ && i < text_.size(); ++i) line += text_[i] == '\n';
        throw Error(ErrorKind::Format, source_ + ": line " + std::to_string(line) + ": " + problem);
    }
    void skip_space() {
        while (pos_ < text_.size() &&
               (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\n' || text_[pos_] == '\r'))
            ++pos_;
    }
    char peek() {
        skip_space();
        if (pos_ == text_.size()) fail("unexpected end of file");
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

    Value value(int depth) {
        if (depth > kMaxDepth) fail("nesting deeper than 64 levels");
        const char c = peek();
        if (c == '{') return object(depth);
        if (c == '[') return array(depth);
        if (c == '"') return Value(string());
        if (literal("true")) return Value(true);
        if (literal("false")) return Value(false);
        if (literal("null")) return Value(nullptr);
        return Value(number());
    }

    Value object(int depth) {
        expect('{');
        Value::Object members;
        if (peek() == '}') {
            ++pos_;
            return Value(std::move(members));
        }
        while (true) {
            if (peek() != '"') fail("expected a member name");
            std::string key = string();
            expect(':');
            members.emplace_back(std::move(key), value(depth + 1));
            if (peek() == '}') break;
            expect(',');
        }
        ++pos_;
        return Value(std::move(members));
    }

    Value array(int depth) {
        expect('[');
        Value::Array items;
        if (peek() == ']') {
            ++pos_;
            return Value(std::move(items));
        }
        while (true) {
            items.push_back(value(depth + 1));
            if (peek() == ']') break;
            expect(',');
        }
        ++pos_;
        return Value(std::move(items));
    }

    std::string string() {
        ++pos_;  // the opening quote
        std::string out;
        while (true) {
            if (pos_ >= text_.size()) fail("unterminated string");
            const char c = text_[pos_++];
            if (c == '"') return out;
            if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
            if (c != '\\') {
                out += c;
                continue;
            }
            if (pos_ >= text_.size()) fail("unterminated string");
            const char e = text_[pos_++];
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case '/': out += '/'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': append_utf8(out, hex4()); break;
                default: fail("bad escape in a string");
            }
        }
    }

    unsigned hex4() {
        if (pos_ + 4 > text_.size()) fail("bad \\u escape");
        unsigned v = 0;
        for (int i = 0; i < 4; ++i) {
            const char h = text_[pos_++];
            v <<= 4;
            if (h >= '0' && h <= '9')
                v |= unsigned(h - '0');
            else if (h >= 'a' && h <= 'f')
                v |= unsigned(h - 'a' + 10);
            else if (h >= 'A' && h <= 'F')
                v |= unsigned(h - 'A' + 10);
            else
                fail("bad \\u escape");
        }
        return v;
    }

    // Manifests hold file and object names; surrogate pairs are not needed there
    // and are rejected rather than mis-decoded.
    void append_utf8(std::string& out, unsigned cp) {
        if (cp >= 0xD800 && cp <= 0xDFFF) fail("surrogate \\u escapes are not supported");
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

    double number() {
        const std::size_t start = pos_;
        auto digits = [&] {
            const std::size_t from = pos_;
            while (pos_ < text_.size() && text_[pos_] >= '0' && text_[pos_] <= '9') ++pos_;
            return pos_ > from;
        };
        if (pos_ < text_.size() && text_[pos_] == '-') ++pos_;
        if (!digits()) fail("expected a value");
        if (pos_ < text_.size() && text_[pos_] == '.' && (++pos_, !digits())) fail("bad number");
        if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
            ++pos_;
            if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
            if (!digits()) fail("bad number");
        }
        const std::string token(text_.substr(start, pos_ - start));
        return std::strtod(token.c_str(), nullptr);  // the grammar above already checked it
    }
};

std::string number_text(double v) {
    if (!std::isfinite(v)) return "null";
    char text[32];
    if (v == std::floor(v) && std::abs(v) < 9007199254740992.0)
        std::snprintf(text, sizeof text, "%.0f", v);
    else
        std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

bool is_flat(const Value& v) {
    auto scalar = [](const Value& x) { return !x.is_array() && !x.is_object(); };
    if (v.is_array()) {
        for (const Value& x : v.array())
            if (!scalar(x)) return false;
    } else if (v.is_object()) {
        for (const auto& [k, x] : v.object())
            if (!scalar(x)) return false;
    }
    return true;
}

void write_to(std::string& out, const Value& v, int indent) {
    if (v.is_null())
        out += "null";
    else if (v.is_bool())
        out += v.boolean() ? "true" : "false";
    else if (v.is_number())
        out += number_text(v.number());
    else if (v.is_string())
        out += quote(v.string());
    if (!v.is_array() && !v.is_object()) return;
    const bool flat = is_flat(v);
    const std::string inner = flat ? "" : "\n" + std::string(std::size_t(indent + 2), ' ');
    const std::string close = flat ? "" : "\n" + std::string(std::size_t(indent), ' ');
    const std::string comma = flat ? ", " : ",";
    out += v.is_array() ? '[' : '{';
    bool first = true;
    auto next = [&] {
        out += first ? inner : comma + inner;
        first = false;
    };
    if (v.is_array()) {
        for (const Value& x : v.array()) {
            next();
            write_to(out, x, indent + 2);
        }
    } else {
        for (const auto& [k, x] : v.object()) {
            next();
            out += quote(k) + ": ";
            write_to(out, x, indent + 2);
        }
    }
    if (!first) out += close;
    out += v.is_array() ? ']' : '}';
}

// The length of the well-formed UTF-8 sequence at text[i] (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF), or 0.
std::size_t utf8_sequence(std::string_view text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = byte(i);
    const std::size_t n = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
    if (n == 0) return 0;  // a continuation byte, C0/C1 (overlong), F5..FF
    // The second byte's range excludes overlong forms (E0, F0), surrogates
    // (ED) and code points above U+10FFFF (F4).
    const unsigned char lo = c == 0xE0 ? 0xA0 : c == 0xF0 ? 0x90 : 0x80;
    const unsigned char hi = c == 0xED ? 0x9F : c == 0xF4 ? 0x8F : 0xBF;
    if (text.size() - i < n || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
    for (std::size_t k = 2; k < n; ++k)
        if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
    return n;
}

}  // namespace

std::string quote(std::string_view text) {
    std::string out = "\"";
    for (std::size_t i = 0; i < text.size();) {
        const char ch = text[i];
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c >= 0x80) {
            // Well-formed UTF-8 passes through; each byte of anything else
            // (a Latin-1 file name) becomes U+FFFD, so the output stays valid.
            const std::size_t n = utf8_sequence(text, i);
            if (n == 0) {
                out += "\\ufffd";
                ++i;
            } else {
                out.append(text.substr(i, n));
                i += n;
            }
            continue;
        }
        if (c == '"' || c == '\\') {
            out += '\\';
            out += ch;
        } else if (c < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", unsigned(c));
            out += escaped;
        } else {
            out += ch;
        }
        ++i;
    }
    return out + "\"";
}

const Value* Value::find(std::string_view key) const {
    if (!is_object()) return nullptr;
    for (const auto& [k, v] : object())
        if (k == key) return &v;
    return nullptr;
}

Value parse(std::string_view text, const std::string& source) { return Parser(text, source).document(); }

std::string write(const Value& value) {
    std::string out;
    write_to(out, value, 0);
    return out + "\n";
}

}  // namespace vkfuse::json

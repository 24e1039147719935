#include "run/run_config.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "io/file_bytes.hpp"
#include "io/json_value.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {
namespace {

constexpr std::size_t kMaxConfigBytes = 1 << 20;

// A string field of the configuration: its text read into the spec
// (throwing Error on a bad value).
template <typename Parse>
void read_text(const json::Value& v, const std::string& key, const std::string& subject, Parse parse) {
    if (!v.is_string()) throw Error(ErrorKind::InvalidArgument, subject + ": \"" + key + "\" must be a string");
    try {
        parse(v.string());
    } catch (const Error& e) {
        if (std::string(e.what()).rfind(subject, 0) == 0) throw;
        throw Error(ErrorKind::InvalidArgument, subject + ": " + e.what());
    }
}

// The fusion's fields, each written and read here alone: run_config_json
// writes them in this order and read_run_config accepts exactly these keys
// beside format, version, sequence and tuned.
struct FusionField {
    const char* key;
    json::Value (*write)(const FusionSpec&);
    void (*read)(const json::Value&, FusionSpec&, const std::string& subject);
};
constexpr FusionField kFusionFields[] = {
    {"method", [](const FusionSpec& f) { return json::Value(std::string(to_string(f.method))); },
     [](const json::Value& v, FusionSpec& f, const std::string& subject) {
         read_text(v, "method", subject, [&](const std::string& t) { f.method = parse_method(t); });
     }},
    {"wavelet", [](const FusionSpec& f) { return json::Value(std::string(to_string(f.wavelet))); },
     [](const json::Value& v, FusionSpec& f, const std::string& subject) {
         read_text(v, "wavelet", subject, [&](const std::string& t) { f.wavelet = parse_wavelet(t); });
     }},
    {"levels", [](const FusionSpec& f) { return json::Value(f.levels); },
     [](const json::Value& v, FusionSpec& f, const std::string& subject) {
         if (!v.is_number()) throw Error(ErrorKind::InvalidArgument, subject + ": \"levels\" must be a number");
         const double levels = v.number();
         if (levels < 0 || levels > 64 || levels != std::floor(levels))
             throw Error(ErrorKind::InvalidArgument, subject + ": \"levels\" must be a whole number from 0 to 64");
         f.levels = int(levels);
     }},
    {"mode", [](const FusionSpec& f) { return json::Value(std::string(to_string(f.mode))); },
     [](const json::Value& v, FusionSpec& f, const std::string& subject) {
         read_text(v, "mode", subject, [&](const std::string& t) { f.mode = parse_wavelet_mode(t); });
     }},
    {"base_rule", [](const FusionSpec& f) { return json::Value(std::string(to_string(f.base_rule))); },
     [](const json::Value& v, FusionSpec& f, const std::string& subject) {
         read_text(v, "base_rule", subject, [&](const std::string& t) { f.base_rule = parse_rule(t, "base_rule"); });
     }},
    {"detail_rule", [](const FusionSpec& f) { return json::Value(std::string(to_string(f.detail_rule))); },
     [](const json::Value& v, FusionSpec& f, const std::string& subject) {
         read_text(v, "detail_rule", subject,
                   [&](const std::string& t) { f.detail_rule = parse_rule(t, "detail_rule"); });
     }},
};

// Every key a configuration may hold, in the order run_config_json writes them.
std::vector<std::string> config_keys() {
    std::vector<std::string> keys{"format", "version", "sequence"};
    for (const FusionField& f : kFusionFields) keys.emplace_back(f.key);
    keys.emplace_back("tuned");
    return keys;
}

const json::Value* member(const json::Value& root, const char* key, bool (json::Value::*is)() const,
                          const std::string& subject, const char* expected, bool required) {
    const json::Value* v = root.find(key);
    if (!v) {
        if (required) throw Error(ErrorKind::InvalidArgument, subject + ": no \"" + key + "\"");
        return nullptr;
    }
    if (!(v->*is)()) throw Error(ErrorKind::InvalidArgument, subject + ": \"" + key + "\" must be " + expected);
    return v;
}

}  // namespace

std::string run_config_json(const RunConfig& c, json::Value tuned) {
    json::Value::Object root{{"format", "vkfuse-config"}, {"version", 1}, {"sequence", to_string(c.sequence)}};
    for (const FusionField& f : kFusionFields) root.emplace_back(f.key, f.write(c.fusion));
    if (!tuned.is_null()) root.emplace_back("tuned", std::move(tuned));
    return json::write(root) + "\n";
}

RunConfig read_run_config(const std::string& path) {
    const std::string subject = "--config " + path;
    std::string text;
    try {
        const std::vector<unsigned char> bytes = io::read_file_bytes(path, kMaxConfigBytes);
        text.assign(bytes.begin(), bytes.end());
    } catch (const Error& e) {
        throw Error(e.kind(), "--config " + std::string(e.what()));
    }
    json::Value root;
    try {
        root = json::parse(text, path);
    } catch (const Error& e) {
        throw Error(ErrorKind::InvalidArgument, "--config " + std::string(e.what()));
    }
    if (!root.is_object()) throw Error(ErrorKind::InvalidArgument, subject + ": not a JSON object");
    // A misspelt key would silently leave its default in force, and of a key
    // given twice one would silently win: both are refused.
    const json::Value::Object& members = root.object();
    const std::vector<std::string> keys = config_keys();
    for (auto it = members.begin(); it != members.end(); ++it) {
        if (std::find(keys.begin(), keys.end(), it->first) == keys.end()) {
            std::string expected;
            for (const std::string& k : keys) expected += (expected.empty() ? "" : ", ") + k;
            throw Error(ErrorKind::InvalidArgument,
                        subject + ": unknown key " + json::quote(it->first) + " (expected " + expected + ")");
        }
        if (std::any_of(members.begin(), it, [&](const auto& m) { return m.first == it->first; }))
            throw Error(ErrorKind::InvalidArgument, subject + ": " + json::quote(it->first) + " given twice");
    }
    const json::Value* format = member(root, "format", &json::Value::is_string, subject, "a string", true);
    if (format->string() != "vkfuse-config")
        throw Error(ErrorKind::InvalidArgument, subject + ": \"format\" is not \"vkfuse-config\"");
    const json::Value* version = member(root, "version", &json::Value::is_number, subject, "a number", true);
    if (version->number() != 1) throw Error(ErrorKind::InvalidArgument, subject + ": version must be 1");
    RunConfig c;
    read_text(*member(root, "sequence", &json::Value::is_string, subject, "a string", true), "sequence", subject,
              [&](const std::string& t) {
                  c.sequence = parse_sequence(t);
                  for (const Illumination& s : c.sequence) s.check(LedLayout::digit());
              });
    for (const FusionField& f : kFusionFields)
        if (const json::Value* v = root.find(f.key)) f.read(*v, c.fusion, subject);
    return c;
}

}  // namespace vkfuse::cli

#include "run_config.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "io/file_bytes.hpp"
#include "io/json_value.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::cli {
namespace {

constexpr std::size_t kMaxConfigBytes = 1 << 20;

// Every key a configuration may hold: what run_config_json writes.
constexpr const char* kConfigKeys[] = {"format", "version", "sequence", "method",      "wavelet",
                                       "levels", "mode",    "base_rule", "detail_rule", "tuned"};

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
    json::Value::Object root{{"format", "vkfuse-config"},
                             {"version", 1},
                             {"sequence", to_string(c.sequence)},
                             {"method", std::string(to_string(c.fusion.method))},
                             {"wavelet", std::string(to_string(c.fusion.wavelet))},
                             {"levels", c.fusion.levels},
                             {"mode", std::string(to_string(c.fusion.mode))},
                             {"base_rule", std::string(to_string(c.fusion.base_rule))},
                             {"detail_rule", std::string(to_string(c.fusion.detail_rule))}};
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
    for (auto it = members.begin(); it != members.end(); ++it) {
        if (std::find(std::begin(kConfigKeys), std::end(kConfigKeys), it->first) == std::end(kConfigKeys)) {
            std::string expected;
            for (const char* k : kConfigKeys) expected += (expected.empty() ? "" : ", ") + std::string(k);
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
    const auto text_of = [&](const char* key, bool required) -> const std::string* {
        const json::Value* v = member(root, key, &json::Value::is_string, subject, "a string", required);
        return v ? &v->string() : nullptr;
    };
    try {
        c.sequence = parse_sequence(*text_of("sequence", true));
        for (const Illumination& s : c.sequence) s.check(LedLayout::digit());
        if (auto v = text_of("method", false)) c.fusion.method = parse_method(*v);
        if (auto v = text_of("wavelet", false)) c.fusion.wavelet = parse_wavelet(*v);
        if (auto v = text_of("mode", false)) c.fusion.mode = parse_wavelet_mode(*v);
        if (auto v = text_of("base_rule", false)) c.fusion.base_rule = parse_rule(*v, "base_rule");
        if (auto v = text_of("detail_rule", false)) c.fusion.detail_rule = parse_rule(*v, "detail_rule");
    } catch (const Error& e) {
        if (std::string(e.what()).rfind(subject, 0) == 0) throw;
        throw Error(ErrorKind::InvalidArgument, subject + ": " + e.what());
    }
    if (const json::Value* v = member(root, "levels", &json::Value::is_number, subject, "a number", false)) {
        const double levels = v->number();
        if (levels < 0 || levels > 64 || levels != std::floor(levels))
            throw Error(ErrorKind::InvalidArgument, subject + ": \"levels\" must be a whole number from 0 to 64");
        c.fusion.levels = int(levels);
    }
    return c;
}

}  // namespace vkfuse::cli

// FusionSpec names, defaults and validation (include/vkfuse/core/fusion.hpp).
#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "core/method_table.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/fusion.hpp"

namespace vkfuse {
namespace {

// One table per enum keeps to_string and parse_* in agreement by construction
// (methods: the method table's names).
template <class E>
using NameTable = std::array<std::pair<E, std::string_view>, 4>;

constexpr NameTable<Wavelet> kWavelets{{{Wavelet::Haar, "haar"},
                                        {Wavelet::Db2, "db2"},
                                        {Wavelet::Bior22, "bior2.2"},
                                        {Wavelet::Bior44, "bior4.4"}}};
constexpr NameTable<Rule> kRules{{{Rule::MaxAbs, "max-abs"},
                                  {Rule::Mean, "mean"},
                                  {Rule::Max, "max"},
                                  {Rule::Min, "min"}}};
constexpr std::array<std::pair<WaveletMode, std::string_view>, 2> kModes{
    {{WaveletMode::Periodization, "periodization"}, {WaveletMode::Symmetric, "symmetric"}}};

template <class Table, class E>
std::string_view name_of(const Table& table, E value) {
    for (const auto& [v, name] : table)
        if (v == value) return name;
    return "?";  // unreachable for valid enumerators; avoids UB on a cast-in value
}

template <class Table>
std::string expected_list(const Table& table) {
    std::string out;
    for (const auto& entry : table) {
        if (!out.empty()) out += ", ";
        out += entry.second;
    }
    return out;
}

// Throws the one-line message the CLI prints, e.g.
// --wavelet: unknown wavelet "db9" (expected haar, db2, bior2.2, bior4.4)
template <class Table>
auto parse_name(const Table& table, std::string_view text, std::string_view option, std::string_view what) {
    for (const auto& [value, name] : table)
        if (name == text) return value;
    throw Error(ErrorKind::InvalidArgument, std::string(option) + ": unknown " + std::string(what) + " \"" +
                                                std::string(text) + "\" (expected " + expected_list(table) + ")");
}

}  // namespace

int FusionSpec::effective_levels() const { return levels != 0 ? levels : core::method_info(method).default_levels; }

std::string_view to_string(Method m) { return core::method_info(m).name; }
std::string_view to_string(Wavelet w) { return name_of(kWavelets, w); }
std::string_view to_string(WaveletMode m) { return name_of(kModes, m); }
std::string_view to_string(Rule r) { return name_of(kRules, r); }

std::string method_label(const FusionSpec& fusion) {
    std::string label(to_string(fusion.method));
    if (core::method_info(fusion.method).uses_wavelet) label += "/" + std::string(to_string(fusion.wavelet));
    return label;
}

Method parse_method(std::string_view s) {
    for (const core::MethodInfo& row : core::method_table())
        if (row.name == s) return row.method;
    throw Error(ErrorKind::InvalidArgument, "--method: unknown method \"" + std::string(s) + "\" (expected " +
                                                core::method_names(", ") + ")");
}
Wavelet parse_wavelet(std::string_view s) { return parse_name(kWavelets, s, "--wavelet", "wavelet"); }
WaveletMode parse_wavelet_mode(std::string_view s) { return parse_name(kModes, s, "--mode", "mode"); }
Rule parse_rule(std::string_view s) { return parse_rule(s, "--base-rule/--detail-rule"); }
Rule parse_rule(std::string_view s, std::string_view option) { return parse_name(kRules, s, option, "rule"); }

int filter_length(Wavelet w) {
    switch (w) {
        case Wavelet::Haar: return 2;
        case Wavelet::Db2: return 4;
        case Wavelet::Bior22: return 6;
        case Wavelet::Bior44: return 10;
    }
    throw Error(ErrorKind::InvalidArgument, "filter_length: invalid wavelet enumerator");
}

int max_wavelet_levels(Wavelet w, int height, int width) {
    // pywt.dwt_max_level: 0 if n < F - 1, else floor(log2(n / (F - 1))) with
    // integer division, where n is the shorter side.
    const int n = std::min(height, width);
    const int f1 = filter_length(w) - 1;
    if (n < f1 || n <= 0) return 0;
    int q = n / f1, level = 0;
    while (q > 1) {
        q /= 2;
        ++level;
    }
    return level;
}

}  // namespace vkfuse

// vkfuse-bench-check-json FILE [--min-cells N] [--require-measured BACKEND]:
// the ctest check that --json output parses and every cell has every field,
// so the report cannot silently lose a column. Exit 0 ok, 1 with one line why.
#include <cmath>
#include <cstdio>
#include <map>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/json_value.hpp"
#include "report.hpp"
#include "vkfuse/core/skip.hpp"

namespace {

using vkfuse::json::Value;

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot be read");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool is_measured(const Value& cell) {
    const Value* skipped = cell.find("skipped");
    return skipped && skipped->is_null();
}

// A measured cell must carry numbers where it measured something.
void check_measured(const Value& cell, std::size_t index) {
    for (const char* key : {"median_ms", "min_ms", "max_ms", "throughput_cycles_s", "max_abs_err", "mean_abs_err"}) {
        const Value* v = cell.find(key);
        if (!v->is_number() || v->number() < 0)
            throw std::runtime_error("cell " + std::to_string(index) + ": \"" + key + "\" is not a non-negative number");
    }
    const Value* m = cell.find("metric_rel_err");
    if (!m->is_object() || !m->find("sharpness") || !m->find("contrast") || !m->find("background_diff"))
        throw std::runtime_error("cell " + std::to_string(index) + ": metric_rel_err lacks a metric");
}

void check(const Value& doc, int min_cells, const std::string& require_backend) {
    if (!doc.is_array()) throw std::runtime_error("top level is not an array");
    if (int(doc.array().size()) < min_cells)
        throw std::runtime_error(std::to_string(doc.array().size()) + " cells, expected at least " + std::to_string(min_cells));
    bool backend_seen = require_backend.empty();
    for (std::size_t i = 0; i < doc.array().size(); ++i) {
        const Value& cell = doc.array()[i];
        if (!cell.is_object()) throw std::runtime_error("cell " + std::to_string(i) + " is not an object");
        for (const auto& key : vkfuse::bench::json_required_fields())
            if (!cell.find(key)) throw std::runtime_error("cell " + std::to_string(i) + " lacks \"" + key + "\"");
        if (!is_measured(cell)) continue;
        check_measured(cell, i);
        const Value* backend = cell.find("backend");
        backend_seen |= backend->is_string() && backend->string() == require_backend;
    }
    if (!backend_seen) throw std::runtime_error("no measured " + require_backend + " cell");
}

// --scenes: every row has every field; no fused cycle differs from full
// fusion (skip idle fuses a changed cycle exactly as skip off); the scene
// with no contact is idle throughout at the default threshold and then costs
// less than full fusion.
void check_scenes(const Value& doc) {
    if (!doc.is_array() || doc.array().empty()) throw std::runtime_error("top level is not a non-empty array");
    bool none_idle = false;
    for (std::size_t i = 0; i < doc.array().size(); ++i) {
        const Value& row = doc.array()[i];
        for (const char* key : {"scene", "skip", "threshold", "contact_fraction", "fused_fraction", "median_ms",
                                "full_median_ms", "time_fraction", "max_abs_err_contact", "max_abs_err_outside",
                                "tiles_work_fraction"})
            if (!row.find(key)) throw std::runtime_error("row " + std::to_string(i) + " lacks \"" + key + "\"");
        const double tiles = row.find("tiles_work_fraction")->number();
        if (!(tiles >= 0 && tiles <= 1))
            throw std::runtime_error("row " + std::to_string(i) + ": tiles_work_fraction outside [0, 1]");
        if (row.find("max_abs_err_contact")->number() != 0)
            throw std::runtime_error("row " + std::to_string(i) + ": a fused cycle differs from full fusion");
        if (row.find("scene")->string() == "none" && row.find("skip")->string() != "off" &&
            row.find("threshold")->number() == vkfuse::SkipConfig{}.threshold) {
            if (row.find("fused_fraction")->number() != 0) throw std::runtime_error("no contact, yet cycles were fused");
            if (tiles != 0) throw std::runtime_error("no contact, yet the tile-sparse model does work");
            if (!(row.find("time_fraction")->number() < 1)) throw std::runtime_error("idle cycles cost full fusion");
            none_idle = true;
        }
    }
    if (!none_idle) throw std::runtime_error("no row for the scene without contact at the default threshold");
}

// --pipeline: every row has every field; each method has a round trip row
// and a row with two cycles in flight, whose results equal the round trip's.
void check_pipeline(const Value& doc) {
    if (!doc.is_array() || doc.array().empty()) throw std::runtime_error("top level is not a non-empty array");
    int round_trips = 0, pipelined = 0;
    for (std::size_t i = 0; i < doc.array().size(); ++i) {
        const Value& row = doc.array()[i];
        for (const char* key : {"method", "levels", "device", "width", "height", "frames", "sensors", "cycles_in_flight",
                                "median_ms", "throughput_cycles_s", "speedup", "max_abs_diff"})
            if (!row.find(key)) throw std::runtime_error("row " + std::to_string(i) + " lacks \"" + key + "\"");
        if (!(row.find("median_ms")->number() > 0) || !(row.find("throughput_cycles_s")->number() > 0))
            throw std::runtime_error("row " + std::to_string(i) + ": no positive time and throughput");
        if (row.find("max_abs_diff")->number() != 0)
            throw std::runtime_error("row " + std::to_string(i) + ": two cycles in flight changed a result");
        (row.find("cycles_in_flight")->number() == 1 ? round_trips : pipelined) += 1;
    }
    if (round_trips == 0 || round_trips != pipelined)
        throw std::runtime_error("not one round trip row and one pipelined row per method");
}

// --windows: every row has every field; a still contact costs a sliding
// window nothing (its frames equal the same instant's); for each scene and K,
// the sliding window fuses K times the cycle's images a second, and on a
// moving contact reaches a change sooner on average than the cycle.
void check_windows(const Value& doc) {
    if (!doc.is_array() || doc.array().empty()) throw std::runtime_error("top level is not a non-empty array");
    std::map<std::string, const Value*> cycle_rows;
    int pairs = 0;
    for (std::size_t i = 0; i < doc.array().size(); ++i) {
        const Value& row = doc.array()[i];
        const std::string at = "row " + std::to_string(i);
        for (const char* key : {"scene", "window", "sequence", "frames", "images", "fused_fps", "latency_mean_ms",
                                "latency_max_ms", "span_max_ms", "max_abs_err", "mean_abs_err", "sharpness_rel_err",
                                "contrast_rel_err", "background_diff_rel_err"})
            if (!row.find(key)) throw std::runtime_error(at + " lacks \"" + key + "\"");
        const std::string scene = row.find("scene")->string();
        const std::string key = scene + " K=" + std::to_string(int(row.find("frames")->number()));
        if (scene == "still" && (row.find("max_abs_err")->number() != 0 || row.find("sharpness_rel_err")->number() != 0))
            throw std::runtime_error(at + ": a still contact, yet an error against the same instant");
        if (row.find("window")->string() == "cycle") {
            cycle_rows[key] = &row;
            continue;
        }
        const auto c = cycle_rows.find(key);
        if (c == cycle_rows.end()) throw std::runtime_error(at + ": no cycle row before it for " + key);
        const double ratio = row.find("fused_fps")->number() / c->second->find("fused_fps")->number();
        if (std::abs(ratio - row.find("frames")->number()) > 0.05)
            throw std::runtime_error(at + ": " + key + " sliding fuses " + std::to_string(ratio) + "x the cycle's rate");
        const Value* slid = row.find("latency_mean_ms");
        const Value* cycled = c->second->find("latency_mean_ms");
        if (scene != "still" && !(slid->is_number() && cycled->is_number() && slid->number() < cycled->number()))
            throw std::runtime_error(at + ": " + key + " sliding is not sooner on a contact change than the cycle");
        ++pairs;
    }
    if (pairs == 0) throw std::runtime_error("no sliding row beside a cycle row");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: vkfuse-bench-check-json FILE [--min-cells N] [--require-measured BACKEND] [--scenes | --pipeline | --windows]\n");
        return 2;
    }
    int min_cells = 1;
    std::string backend;
    bool scenes = false, pipeline = false, windows = false;
    for (int i = 2; i < argc; ++i) {
        if (std::string(argv[i]) == "--scenes") scenes = true;
        if (std::string(argv[i]) == "--windows") windows = true;
        if (std::string(argv[i]) == "--pipeline") pipeline = true;
    }
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string opt = argv[i];
        if (opt == "--min-cells") min_cells = std::atoi(argv[i + 1]);
        if (opt == "--require-measured") backend = argv[i + 1];
    }
    try {
        const Value doc = vkfuse::json::parse(read_file(argv[1]), argv[1]);
        if (scenes)
            check_scenes(doc);
        else if (windows)
            check_windows(doc);
        else if (pipeline)
            check_pipeline(doc);
        else
            check(doc, min_cells, backend);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
        return 1;
    }
    std::printf("%s: ok\n", argv[1]);
    return 0;
}

#include "run_output.hpp"

#include <algorithm>
#include <filesystem>

#include "json.hpp"
#include "vkfuse/error.hpp"
#include "vkfuse/io.hpp"

namespace vkfuse::cli {
namespace {

namespace fs = std::filesystem;

void make_directory(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(ErrorKind::Io, dir.string() + ": cannot create: " + ec.message());
}

std::string cycle_name(std::uint64_t cycle) {
    char name[32];
    std::snprintf(name, sizeof name, "%06llu.png", static_cast<unsigned long long>(cycle));
    return name;
}

// static frame (8-bit) | fused frame, 8 grey columns apart.
Image side_by_side(const Frame& still, const Image& fused) {
    constexpr int kGap = 8;
    Image out(still.height, still.width * 2 + kGap, 3);
    std::fill(out.data.begin(), out.data.end(), 0.5f);
    for (int y = 0; y < still.height; ++y)
        for (int x = 0; x < still.width; ++x)
            for (int c = 0; c < 3; ++c) {
                out.at(y, x, c) = float(still.pixels[(std::size_t(y) * still.width + x) * 3 + c]) / 255.0f;
                out.at(y, still.width + kGap + x, c) = fused.at(y, x, c);
            }
    return out;
}

void write_text(const std::string& path, const std::string& text) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw Error(ErrorKind::Io, path + ": cannot write");
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok) throw Error(ErrorKind::Io, path + ": write failed");
}

}  // namespace

std::string metrics_line(const CycleResult& cycle, const SensorCycle& s, const std::string& object) {
    std::string line = "{\"cycle\": " + std::to_string(cycle.cycle) + ", \"sensor\": " + json_string(s.serial) +
                       ", \"status\": " + json_string(std::string(to_string(s.status)));
    if (s.status != SensorStatus::Ok) return line + ", \"error\": " + json_string(s.error) + "}";
    std::string frames;
    for (const Frame& f : s.frames) frames += (frames.empty() ? "" : ", ") + std::to_string(f.index);
    line += ", \"object\": " + json_string(object) + ", \"timestamp\": " + json_number(s.frames.back().timestamp) +
            ", \"frames\": [" + frames + "], \"sharpness\": " + json_number(s.metrics.sharpness) +
            ", \"contrast\": " + json_number(s.metrics.contrast);
    if (s.metrics.background_diff) line += ", \"background_diff\": " + json_number(*s.metrics.background_diff);
    return line + "}";
}

std::size_t static_slot(const IlluminationSequence& sequence, const LedLayout& leds) {
    const Illumination full(std::vector<int>(std::size_t(leds.channels), leds.max_level));
    auto it = std::find(sequence.begin(), sequence.end(), full);
    return it == sequence.end() ? 0 : std::size_t(it - sequence.begin());
}

RunOutput::RunOutput(std::string directory, std::string object, std::size_t slot)
    : directory_(std::move(directory)), object_(std::move(object)), static_slot_(slot) {
    make_directory(directory_);
    const std::string path = (fs::path(directory_) / "metrics.jsonl").string();
    metrics_ = std::fopen(path.c_str(), "wb");
    if (!metrics_) throw Error(ErrorKind::Io, path + ": cannot write");
}

RunOutput::~RunOutput() {
    if (metrics_) std::fclose(metrics_);
}

void RunOutput::write(const CycleResult& cycle) {
    for (const SensorCycle& s : cycle.sensors) {
        std::fprintf(metrics_, "%s\n", metrics_line(cycle, s, object_).c_str());
        if (s.status != SensorStatus::Ok || !s.fused) continue;
        const fs::path dir = fs::path(directory_) / "fused" / s.serial;
        make_directory(dir);
        io::write_image((dir / cycle_name(cycle.cycle)).string(), *s.fused);
        auto it = std::find_if(last_.begin(), last_.end(), [&](const auto& e) { return e.first == s.serial; });
        if (it == last_.end()) it = last_.insert(last_.end(), {s.serial, {}});
        it->second = {s.frames, *s.fused};
    }
    std::fflush(metrics_);  // a Ctrl-C or a crash later keeps every finished cycle
}

void RunOutput::finish(const std::string& summary_json) {
    const fs::path dir = fs::path(directory_) / "side_by_side";
    for (const auto& [serial, last] : last_) {
        make_directory(dir);
        io::write_image((dir / (object_ + "_" + serial + ".png")).string(),
                        side_by_side(last.frames.at(static_slot_), last.fused));
    }
    write_text((fs::path(directory_) / "summary.json").string(), summary_json + "\n");
    if (metrics_ && std::fclose(metrics_) != 0) {
        metrics_ = nullptr;
        throw Error(ErrorKind::Io, (fs::path(directory_) / "metrics.jsonl").string() + ": write failed");
    }
    metrics_ = nullptr;
}

}  // namespace vkfuse::cli

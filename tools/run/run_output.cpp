#include "run/run_output.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "io/path_component.hpp"
#include "run/caption.hpp"
#include "standard_output.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/reference.hpp"

namespace vkfuse::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMetricsName = "metrics.jsonl";
constexpr const char* kSummaryName = "summary.json";
constexpr const char* kFusedName = "fused";
constexpr const char* kSideBySideName = "side_by_side";

void make_directory(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(ErrorKind::Io, dir.string() + ": cannot create: " + ec.message());
}

// All of text in as few write() calls as the kernel allows: one for a line of
// any length on a local file system, so a kill never leaves half a line.
void write_all(int fd, const std::string& text, const std::string& path) {
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw Error(ErrorKind::Io, path + ": write failed: " + std::strerror(n < 0 ? errno : ENOSPC));
        done += std::size_t(n);
    }
}

std::string cycle_name(std::uint64_t cycle) {
    char name[32];
    std::snprintf(name, sizeof name, "%06llu.png", static_cast<unsigned long long>(cycle));
    return name;
}

constexpr int kSideBySideGap = 8;

// static frame (8-bit) | fused frame, 8 grey columns apart.
Image side_by_side(const Frame& still, const Image& fused) {
    constexpr int kGap = kSideBySideGap;
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
    const int fd = create_new_file(path);
    try {
        write_all(fd, text, path);
    } catch (...) {
        ::close(fd);
        throw;
    }
    if (::close(fd) != 0) throw Error(ErrorKind::Io, path + ": write failed: " + std::strerror(errno));
}

bool same_bits(const Image& a, const Image& b) {
    return a.height == b.height && a.width == b.width && a.channels == b.channels &&
           std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

}  // namespace

std::string metrics_line(const CycleResult& cycle, const SensorCycle& s, const std::string& object, bool skipping,
                         std::optional<std::uint64_t> image_from_cycle) {
    std::string line = "{\"cycle\": " + std::to_string(cycle.cycle) + ", \"sensor\": " + json_string(s.serial) +
                       ", \"status\": " + json_string(std::string(to_string(s.status)));
    if (s.status != SensorStatus::Ok) return line + ", \"error\": " + json_string(s.error) + "}";
    std::string frames;
    for (const Frame& f : s.frames) frames += (frames.empty() ? "" : ", ") + std::to_string(f.index);
    line += ", \"object\": " + json_string(object) + ", \"timestamp\": " + json_number(s.newest_timestamp()) +
            ", \"frames\": [" + frames + "], \"window_span_s\": " + json_number(s.window_span_s());
    // Only the metrics the run asked for (--metrics): the others read NaN.
    const auto metric = [&](Metric m, double v) {
        if (!std::isnan(v)) line += ", " + json_string(std::string(to_string(m))) + ": " + json_number(v);
    };
    metric(Metric::Sharpness, s.metrics.sharpness);
    metric(Metric::Contrast, s.metrics.contrast);
    if (s.metrics.background_diff) metric(Metric::BackgroundDiff, *s.metrics.background_diff);
    line += std::string(", \"idle\": ") + (s.skip.idle ? "true" : "false") +
            ", \"fused_fraction\": " + json_number(s.skip.fused_fraction);
    if (skipping) {
        line += ", \"change_score\": " + json_number(s.skip.score);
        if (s.skip.reused) line += ", \"reused\": true";
        const SkipRegion& r = s.skip.fused_region;
        if (s.skip.fused_fraction > 0 && s.skip.fused_fraction < 1)
            line += ", \"fused_region\": [" + std::to_string(r.top) + ", " + std::to_string(r.height) + ", " +
                    std::to_string(r.left) + ", " + std::to_string(r.width) + "]";
        if (s.watch) line += ", \"watch\": true";
    }
    if (image_from_cycle) line += ", \"image_from_cycle\": " + std::to_string(*image_from_cycle);
    return line + "}";
}

std::size_t static_slot(const IlluminationSequence& sequence, const LedLayout& leds) {
    const Illumination full(std::vector<int>(std::size_t(leds.channels), leds.max_level));
    auto it = std::find(sequence.begin(), sequence.end(), full);
    return it == sequence.end() ? 0 : std::size_t(it - sequence.begin());
}

bool is_run_output_entry(const std::string& name) {
    return name == kMetricsName || name == kSummaryName || name == kFusedName || name == kSideBySideName;
}

// Fused frames waiting for the PNG writer: a few cycles of 16 VGA sensors.
constexpr std::size_t kMaxPendingImageBytes = std::size_t(256) << 20;

RunOutput::RunOutput(std::string directory, std::string object, RunOutputLabels labels, bool skipping)
    : directory_(std::move(directory)),
      object_(std::move(object)),
      labels_(std::move(labels)),
      skipping_(skipping),
      fused_pngs_(kMaxPendingImageBytes) {
    io::check_plain_component(object_, "object");
    metrics_fd_ = create_new_file((fs::path(directory_) / kMetricsName).string());
}

RunOutput::~RunOutput() {
    if (metrics_fd_ >= 0) ::close(metrics_fd_);
}

void RunOutput::write(const CycleResult& cycle) {
    const std::string metrics_path = (fs::path(directory_) / kMetricsName).string();
    for (const SensorCycle& s : cycle.sensors) {
        if (s.status != SensorStatus::Ok || !s.fused) {
            write_all(metrics_fd_, metrics_line(cycle, s, object_, skipping_) + "\n", metrics_path);
            continue;
        }
        io::check_plain_component(s.serial, "serial");
        const fs::path dir = fs::path(directory_) / kFusedName / s.serial;
        const std::string path = (dir / cycle_name(cycle.cycle)).string();
        // An idle or reused cycle usually hands back the image of an earlier
        // one: that file gets a second name instead of a second encoding.
        Written& last_written = written_[s.serial];
        std::optional<std::uint64_t> image_from;
        if (last_written.image && same_bits(*last_written.image, *s.fused)) {
            image_from = last_written.cycle;
        } else {
            if (!last_written.image) make_directory(dir);
            last_written = {std::make_shared<const Image>(*s.fused), path, cycle.cycle};
        }
        write_all(metrics_fd_, metrics_line(cycle, s, object_, skipping_, image_from) + "\n", metrics_path);
        if (image_from) fused_pngs_.push_link(path, last_written.path);
        else fused_pngs_.push_png(path, last_written.image);
        if (s.watch) continue;  // one setting only: the side-by-side picture shows a whole cycle
        auto it = std::find_if(last_.begin(), last_.end(), [&](const auto& e) { return e.first == s.serial; });
        if (it == last_.end()) it = last_.insert(last_.end(), {s.serial, {}});
        it->second = {s.frames.at(labels_.static_slot), last_written.image, s.metrics, cycle.cycle};
    }
}

void RunOutput::add_background(const std::string& serial, const Illumination& setting, const std::vector<Frame>& frames) {
    if (frames.empty() || labels_.static_slot >= labels_.sequence.size() || setting != labels_.sequence[labels_.static_slot])
        return;
    ImageD mean(frames.front().height, frames.front().width, 3);
    for (const Frame& f : frames)
        for (std::size_t i = 0; i < mean.data.size() && i < f.pixels.size(); ++i)
            mean.data[i] += double(f.pixels[i]) / 255.0 / double(frames.size());
    std::lock_guard lock(backgrounds_mutex_);
    static_backgrounds_[serial] = std::move(mean);
}

// [static | fused] under three lines: what each side is, the fused image's
// metrics over the static frame's (the paper's gains; above 1: better), and
// whose picture it is.
Image RunOutput::captioned_side_by_side(const std::string& serial, const Last& last) const {
    const Frame& still = last.still;
    ImageD frame(still.height, still.width, 3);
    for (std::size_t i = 0; i < frame.data.size(); ++i) frame.data[i] = double(still.pixels[i]) / 255.0;
    const auto bg = static_backgrounds_.find(serial);
    const bool with_bg = bg != static_backgrounds_.end() && bg->second.same_shape(frame) && last.metrics.background_diff;
    const Metrics base = metrics_reference(frame, with_bg ? &bg->second : nullptr, labels_.metrics);
    std::string gains;
    const auto gain = [&](const char* name, double fused, double still_value) {
        if (std::isnan(fused) || std::isnan(still_value) || still_value <= 0) return;
        char text[64];
        std::snprintf(text, sizeof text, "%s%s x%.3f", gains.empty() ? "" : "   ", name, fused / still_value);
        gains += text;
    };
    gain("sharpness", last.metrics.sharpness, base.sharpness);
    gain("contrast", last.metrics.contrast, base.contrast);
    if (with_bg && base.background_diff) gain("background diff", *last.metrics.background_diff, *base.background_diff);
    const Image pair = side_by_side(still, *last.fused);
    const int scale = std::max(1, pair.width / 700);
    const std::vector<CaptionLine> lines = {
        {{"static " + labels_.sequence[labels_.static_slot].to_string(), 0},
         {"fused " + to_string(labels_.sequence) + "  " + labels_.method, still.width + kSideBySideGap}},
        {{"gains over static: " + (gains.empty() ? std::string("none measured") : gains), 0}},
        {{object_ + "  " + serial + "  cycle " + std::to_string(last.cycle), 0}}};
    return with_caption(pair, lines, scale);
}

void RunOutput::finish(const std::string& summary_json) {
    fused_pngs_.drain();
    const fs::path dir = fs::path(directory_) / kSideBySideName;
    for (const auto& [serial, last] : last_) {
        make_directory(dir);
        const std::string name = object_ + "_" + serial + ".png";
        io::check_plain_component(name, "side-by-side picture");
        std::lock_guard lock(backgrounds_mutex_);
        io::write_image((dir / name).string(), captioned_side_by_side(serial, last));
    }
    write_text((fs::path(directory_) / kSummaryName).string(), summary_json + "\n");
    const int fd = metrics_fd_;
    metrics_fd_ = -1;
    if (::close(fd) != 0)
        throw Error(ErrorKind::Io, (fs::path(directory_) / kMetricsName).string() + ": write failed: " +
                                       std::strerror(errno));
}

}  // namespace vkfuse::cli

#include "peer.hpp"

#include <filesystem>
#include <stdexcept>

#include "io/json_value.hpp"
#include "process.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::bench {
namespace {

double number_field(const json::Value& v, std::string_view key) {
    const json::Value* f = v.find(key);
    if (!f || !f->is_number())
        throw std::runtime_error("peer output lacks the number \"" + std::string(key) + "\"");
    return f->number();
}

std::vector<std::string> peer_command(std::vector<std::string> argv, const Cell& cell, const std::filesystem::path& dir,
                                      int frames, double max_seconds, int runs) {
    argv.insert(argv.end(), {"--method", std::string(to_string(cell.method.method))});
    if (cell.method.has_wavelet()) argv.insert(argv.end(), {"--wavelet", std::string(to_string(cell.method.wavelet))});
    if (cell.levels > 0) argv.insert(argv.end(), {"--levels", std::to_string(cell.levels)});
    argv.insert(argv.end(), {"--runs", std::to_string(runs), "--max-seconds", std::to_string(max_seconds),
                             "--background", (dir / "background.npy").string(), "--out", (dir / "fused.npy").string()});
    for (int k = 0; k < frames; ++k) argv.push_back((dir / ("frame" + std::to_string(k) + ".npy")).string());
    return argv;
}

// Reads the script's JSON answer and fused image into r and measures its error.
void read_answer(const std::string& stdout_text, const std::filesystem::path& fused_path, const Expected& sensor0,
                 PeerResult& r) {
    const std::string answer = last_line(stdout_text);
    if (answer.empty()) throw std::runtime_error("the peer printed nothing on stdout");
    const json::Value v = json::parse(answer, "peer output");
    const json::Value* name = v.find("peer");
    r.name = name && name->is_string() ? name->string() : "python";
    r.per_sensor.median_ms = number_field(v, "median_ms");
    r.per_sensor.min_ms = number_field(v, "min_ms");
    r.per_sensor.max_ms = number_field(v, "max_ms");
    r.per_sensor.runs = int(number_field(v, "runs"));
    Metrics m;
    m.sharpness = number_field(v, "sharpness");
    m.contrast = number_field(v, "contrast");
    m.background_diff = number_field(v, "background_diff");
    r.metric_error.add(m, sensor0.metrics);
    r.error.add(io::read_image(fused_path.string()), sensor0.fused);
}

}  // namespace

PeerRunner::PeerRunner(std::string script, const std::string& python) : script_(std::move(script)) {
    if (!std::filesystem::exists(script_)) {
        why_not_ = "peer script " + script_ + " not found";
        return;
    }
    const std::vector<std::string> candidates =
        python.empty() ? std::vector<std::string>{"/usr/bin/python3", "python3"} : std::vector<std::string>{python};
    for (const auto& candidate : candidates) {
        const auto r = run_process({candidate, "-c", "import numpy, pywt, cv2"});
        if (r.started && r.exit_code == 0) {
            python_ = candidate;
            prefix_ = {python_, script_};
            return;
        }
        why_not_ += (why_not_.empty() ? "" : "; ") + candidate + ": " + (r.started ? last_line(r.err) : "not found");
    }
}

PeerRunner PeerRunner::program(const std::string& program, std::vector<Method> methods) {
    PeerRunner r;
    r.only_ = std::move(methods);
    if (program.empty())
        r.why_not_ = "not built (OpenCV not found when configured; libopencv-dev provides it)";
    else if (!std::filesystem::exists(program))
        r.why_not_ = program + " not found";
    else
        r.prefix_ = {program};
    return r;
}

std::string PeerRunner::methods() const {
    std::string out;
    for (Method m : only_) out += (out.empty() ? "" : ", ") + std::string(to_string(m));
    return out;
}

PeerResult PeerRunner::run(const Cell& cell, const Inputs& in, const Expected& sensor0, double max_seconds,
                           int runs) const {
    PeerResult r;
    try {
        TempDir dir;
        for (int k = 0; k < in.frames(); ++k)
            io::write_image((dir.path() / ("frame" + std::to_string(k) + ".npy")).string(), in.frame(sensor0.sensor, k));
        io::write_image((dir.path() / "background.npy").string(), in.background(sensor0.sensor));
        const auto p = run_process(peer_command(prefix_, cell, dir.path(), in.frames(), max_seconds, runs));
        if (!p.started) throw std::runtime_error(prefix_.front() + " could not be started");
        if (p.exit_code != 0) throw std::runtime_error("exit " + std::to_string(p.exit_code) + ": " + last_line(p.err));
        read_answer(p.out, dir.path() / "fused.npy", sensor0, r);
    } catch (const std::exception& e) {  // vkfuse::Error (files) and std::runtime_error alike
        r.failure = e.what();
    }
    return r;
}

}  // namespace vkfuse::bench

#include "io/memory_available.hpp"

#include <sys/resource.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "vkfuse/core/error.hpp"

namespace vkfuse::io {
namespace {

// The value after "key:" in a /proc file of "Key:   123 kB" lines, in bytes.
std::optional<std::uint64_t> proc_kib(const char* file, std::string_view key) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.compare(0, key.size(), key) != 0 || line.size() <= key.size() || line[key.size()] != ':') continue;
        std::istringstream fields(line.substr(key.size() + 1));
        std::uint64_t kib = 0;
        if (fields >> kib) return kib * 1024;
    }
    return std::nullopt;
}

// A whole file holding one number ("max" is no limit).
std::optional<std::uint64_t> file_number(const std::string& path) {
    std::ifstream in(path);
    std::string word;
    if (!(in >> word) || word.empty() || !std::isdigit(static_cast<unsigned char>(word[0]))) return std::nullopt;
    return std::strtoull(word.c_str(), nullptr, 10);
}

// "key value" lines (memory.stat).
std::optional<std::uint64_t> stat_value(const std::string& path, std::string_view key) {
    std::ifstream in(path);
    std::string k;
    std::uint64_t v = 0;
    while (in >> k >> v)
        if (k == key) return v;
    return std::nullopt;
}

struct Candidate {
    std::uint64_t bytes;
    std::string source;
};

void consider(std::optional<Candidate>& best, std::uint64_t bytes, std::string source) {
    if (!best || bytes < best->bytes) best = Candidate{bytes, std::move(source)};
}

void rlimit(std::optional<Candidate>& best, int resource, const char* name, const char* status_key) {
    struct rlimit lim {};
    if (::getrlimit(resource, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return;
    const std::uint64_t used = proc_kib("/proc/self/status", status_key).value_or(0);
    consider(best, lim.rlim_cur > used ? std::uint64_t(lim.rlim_cur) - used : 0, name);
}

// Every directory from the cgroup's own up to the hierarchy's root: each
// level's limit applies.
std::vector<std::string> cgroup_levels(const std::string& mount, std::string path) {
    std::vector<std::string> dirs;
    while (true) {
        dirs.push_back(mount + path);
        if (path.empty() || path == "/") break;
        const std::size_t slash = path.rfind('/');
        path = slash == 0 || slash == std::string::npos ? "/" : path.substr(0, slash);
    }
    return dirs;
}

void cgroup_limit(std::optional<Candidate>& best, const std::string& dir, const char* limit_file,
                  const char* usage_file, const char* inactive_key, const char* source) {
    const auto limit = file_number(dir + "/" + limit_file);
    if (!limit || *limit >= (std::uint64_t(1) << 62)) return;  // v1 writes "no limit" as about 2^63
    const std::uint64_t usage = file_number(dir + "/" + usage_file).value_or(0);
    const std::uint64_t cache = stat_value(dir + "/memory.stat", inactive_key).value_or(0);
    const std::uint64_t used = usage > cache ? usage - cache : 0;
    consider(best, *limit > used ? *limit - used : 0, source);
}

void cgroups(std::optional<Candidate>& best) {
    std::ifstream in("/proc/self/cgroup");
    std::string line;
    while (std::getline(in, line)) {
        // "hierarchy-ID:controller-list:cgroup-path"
        const std::size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
        if (b == std::string::npos) continue;
        const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
        if (line.compare(0, a, "0") == 0 && controllers.empty()) {
            for (const std::string& dir : cgroup_levels("/sys/fs/cgroup", path))
                cgroup_limit(best, dir, "memory.max", "memory.current", "inactive_file", "cgroup memory.max");
        } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
            for (const std::string& dir : cgroup_levels("/sys/fs/cgroup/memory", path))
                cgroup_limit(best, dir, "memory.limit_in_bytes", "memory.usage_in_bytes", "total_inactive_file",
                             "cgroup memory.limit_in_bytes");
        }
    }
}

}  // namespace

std::optional<std::uint64_t> parse_byte_count(std::string_view text) {
    std::size_t i = 0;
    std::uint64_t value = 0;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
        if (value > (UINT64_MAX - 9) / 10) return std::nullopt;
        value = value * 10 + std::uint64_t(text[i++] - '0');
    }
    if (i == 0) return std::nullopt;
    std::string unit;
    for (; i < text.size(); ++i) unit += char(std::toupper(static_cast<unsigned char>(text[i])));
    int shift = 0;
    if (!unit.empty() && unit != "B") {
        const std::string units = "KMGT";
        const std::size_t at = units.find(unit[0]);
        const std::string rest = unit.substr(1);
        if (at == std::string::npos || !(rest.empty() || rest == "B" || rest == "IB")) return std::nullopt;
        shift = 10 * int(at + 1);
    }
    if (shift && value > (UINT64_MAX >> shift)) return std::nullopt;
    return value << shift;
}

std::optional<MemoryAvailable> available_memory() {
    std::optional<Candidate> best;
    if (auto avail = proc_kib("/proc/meminfo", "MemAvailable")) consider(best, *avail, "MemAvailable");
    rlimit(best, RLIMIT_AS, "RLIMIT_AS", "VmSize");
    rlimit(best, RLIMIT_DATA, "RLIMIT_DATA", "VmData");
    cgroups(best);
    if (const char* env = std::getenv("VKFUSE_MEMORY_LIMIT"); env && *env) {
        const auto limit = parse_byte_count(env);
        if (!limit)
            throw Error(ErrorKind::InvalidArgument, "VKFUSE_MEMORY_LIMIT=" + std::string(env).substr(0, 40) +
                                                        ": expected a byte count such as 4G, 512M or 1073741824");
        consider(best, *limit, "VKFUSE_MEMORY_LIMIT");
    }
    if (!best) return std::nullopt;
    return MemoryAvailable{best->bytes, best->source};
}

std::string memory_text(double bytes, int decimals) {
    static const char* const kUnits[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
    int unit = 0;
    while (bytes >= 1024 && unit < 5) {
        bytes /= 1024;
        ++unit;
    }
    char text[48];
    std::snprintf(text, sizeof text, "%.*f %s", unit >= 3 ? decimals : 0, bytes, kUnits[unit]);
    return text;
}

}  // namespace vkfuse::io

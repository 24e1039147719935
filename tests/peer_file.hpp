// Reader for the peer vectors under tests/data/peers (written by
// tests/peers/gen_vectors.py; the format is described there). Header-only so
// every test executable can use it without a CMake change.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/plane.hpp"
#include "test_support.hpp"
#include "vkfuse/core/image.hpp"

namespace vkfuse::test {

// One array, every dtype widened to double (float32 and uint8 widen exactly).
struct PeerArray {
    std::vector<int> shape;
    std::vector<double> values;
};

class PeerFile {
public:
    explicit PeerFile(const std::string& name) {
        const std::string path = data_path("peers/" + name);
        std::ifstream in(path, std::ios::binary);
        if (!in) throw std::runtime_error(path + ": cannot open (run tests/peers/gen_vectors.py)");
        char magic[8];
        in.read(magic, 8);
        if (!in || std::memcmp(magic, "VKPEER01", 8) != 0) throw std::runtime_error(path + ": not a peer file");
        const std::uint32_t count = read_u32(in);
        for (std::uint32_t r = 0; r < count; ++r) read_record(in, path);
    }

    const PeerArray& at(const std::string& key) const {
        auto it = arrays_.find(key);
        if (it == arrays_.end()) throw std::out_of_range("peer vector missing: " + key);
        return it->second;
    }
    bool has(const std::string& key) const { return arrays_.count(key) != 0; }
    const std::map<std::string, PeerArray>& all() const { return arrays_; }

    // A 2-D array as a plane.
    core::Plane plane(const std::string& key) const {
        const PeerArray& a = at(key);
        if (a.shape.size() != 2) throw std::runtime_error(key + ": not 2-D");
        core::Plane p(a.shape[0], a.shape[1]);
        p.data = a.values;
        return p;
    }
    // An (H, W, C) array as an image.
    ImageD image(const std::string& key) const {
        const PeerArray& a = at(key);
        if (a.shape.size() != 3) throw std::runtime_error(key + ": not 3-D");
        ImageD img(a.shape[0], a.shape[1], a.shape[2]);
        img.data = a.values;
        return img;
    }
    // A (K, H, W, C) array as K images.
    std::vector<ImageD> frames(const std::string& key) const {
        const PeerArray& a = at(key);
        if (a.shape.size() != 4) throw std::runtime_error(key + ": not 4-D");
        std::vector<ImageD> out;
        const std::size_t n = std::size_t(a.shape[1]) * a.shape[2] * a.shape[3];
        for (int k = 0; k < a.shape[0]; ++k) {
            ImageD img(a.shape[1], a.shape[2], a.shape[3]);
            img.data.assign(a.values.begin() + k * n, a.values.begin() + (k + 1) * n);
            out.push_back(std::move(img));
        }
        return out;
    }

private:
    static std::uint32_t read_u32(std::ifstream& in) {
        unsigned char b[4];
        in.read(reinterpret_cast<char*>(b), 4);
        if (!in) throw std::runtime_error("peer file truncated");
        return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
    }

    template <class T>
    static void read_values(std::ifstream& in, std::vector<double>& out) {
        std::vector<T> raw(out.size());
        in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * sizeof(T)));
        for (std::size_t i = 0; i < raw.size(); ++i) out[i] = double(raw[i]);
    }

    void read_record(std::ifstream& in, const std::string& path) {
        std::string key(read_u32(in), '\0');
        in.read(key.data(), std::streamsize(key.size()));
        const std::uint32_t dtype = read_u32(in), ndim = read_u32(in);
        PeerArray a;
        std::size_t n = 1;
        for (std::uint32_t d = 0; d < ndim; ++d) {
            a.shape.push_back(int(read_u32(in)));
            n *= std::size_t(a.shape.back());
        }
        a.values.resize(n);
        // The generator writes little-endian; so does every machine vkfuse targets.
        static_assert(sizeof(double) == 8 && sizeof(float) == 4);
        if (dtype == 0) read_values<double>(in, a.values);
        else if (dtype == 1) read_values<float>(in, a.values);
        else if (dtype == 2) read_values<std::uint8_t>(in, a.values);
        else throw std::runtime_error(path + ": " + key + ": unknown dtype");
        if (!in) throw std::runtime_error(path + ": " + key + ": truncated");
        arrays_.emplace(std::move(key), std::move(a));
    }

    std::map<std::string, PeerArray> arrays_;
};

// Largest |a - b| of two planes of one shape (throws if the shapes differ).
inline double max_abs_diff(const core::Plane& a, const core::Plane& b) {
    if (!a.same_shape(b)) throw std::invalid_argument("max_abs_diff: plane shapes differ");
    double m = 0;
    for (std::size_t i = 0; i < a.data.size(); ++i) m = std::max(m, std::abs(a.data[i] - b.data[i]));
    return m;
}

}  // namespace vkfuse::test

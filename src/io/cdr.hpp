// io/cdr.hpp - ROS 2's serialization: the plain CDR (XCDR1, little endian)
// that rmw implementations put on the wire and rosbag2 stores in MCAP
// ("cdr" message encoding). A payload starts with the 4-byte encapsulation
// header 00 01 00 00; every primitive is aligned to its size, counted from
// the end of that header; a string is a u32 length counting its NUL, the
// bytes and the NUL; a sequence a u32 count and its elements.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace vkfuse::io::cdr {

class Writer {
public:
    Writer() { out_.assign("\x00\x01\x00\x00", 4); }

    template <class T>
    Writer& num(T x) {
        align(sizeof(T));
        char b[sizeof(T)];
        std::memcpy(b, &x, sizeof(T));  // little-endian hosts only (vkfuse's)
        out_.append(b, sizeof(T));
        return *this;
    }
    Writer& str(std::string_view s) {
        num(std::uint32_t(s.size() + 1));
        out_.append(s);
        out_.push_back('\0');
        return *this;
    }
    // A sequence<uint8> (uint8[]).
    Writer& octets(const void* data, std::size_t n) {
        num(std::uint32_t(n));
        out_.append(static_cast<const char*>(data), n);
        return *this;
    }
    Writer& count(std::size_t n) { return num(std::uint32_t(n)); }
    // A std_msgs/Header: its stamp (builtin_interfaces/Time: int32 seconds,
    // uint32 nanoseconds) time_ns after the epoch, then frame_id.
    Writer& header(std::uint64_t time_ns, std::string_view frame_id) {
        return num(std::int32_t(time_ns / 1'000'000'000u)).num(std::uint32_t(time_ns % 1'000'000'000u)).str(frame_id);
    }

    const std::string& bytes() const { return out_; }
    std::string take() { return std::move(out_); }

private:
    void align(std::size_t n) {
        const std::size_t body = out_.size() - 4;
        out_.append((n - body % n) % n, '\0');
    }
    std::string out_;
};

// Reads a payload without reading past it: a field that does not fit sets
// failed() and reads as zero or empty.
class Reader {
public:
    explicit Reader(std::string_view payload) : data_(payload) {
        if (data_.size() < 4 || data_[0] != 0 || data_[1] != 1) failed_ = true;
        at_ = 4;
    }
    template <class T>
    T num() {
        at_ += (sizeof(T) - (at_ - 4) % sizeof(T)) % sizeof(T);
        T x{};
        if (failed_ || at_ > data_.size() || data_.size() - at_ < sizeof(T)) {
            failed_ = true;
            return x;
        }
        std::memcpy(&x, data_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return x;
    }
    std::string_view str() {
        const std::uint32_t n = num<std::uint32_t>();
        if (n == 0) return {};  // some writers send an empty string as length 0
        const std::string_view b = bytes(n);
        if (failed_ || b.back() != '\0') {
            failed_ = true;
            return {};
        }
        return b.substr(0, b.size() - 1);
    }
    std::string_view octets() { return bytes(num<std::uint32_t>()); }
    // A sequence's count, refused when even elements of min_bytes each could not fit.
    std::uint32_t count(std::size_t min_bytes) {
        const std::uint32_t n = num<std::uint32_t>();
        if (!failed_ && std::uint64_t(n) * min_bytes > data_.size() - at_) failed_ = true;
        return failed_ ? 0 : n;
    }
    bool failed() const { return failed_; }

private:
    std::string_view bytes(std::uint64_t n) {
        if (failed_ || n > data_.size() - at_) {
            failed_ = true;
            return {};
        }
        const std::string_view b = data_.substr(at_, std::size_t(n));
        at_ += std::size_t(n);
        return b;
    }
    std::string_view data_;
    std::size_t at_ = 0;
    bool failed_ = false;
};

}  // namespace vkfuse::io::cdr

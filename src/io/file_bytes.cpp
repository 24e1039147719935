#include "io/file_bytes.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "io/io_error.hpp"

namespace vkfuse::io {

InputFile::InputFile(const std::string& path) : path_(path) {
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer
    // forever; this way it opens at once and fails the regular-file check. It
    // changes nothing for regular files.
    fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) fail(ErrorKind::Io, path, "cannot open: " + system_message(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0) {
        const int err = errno;
        ::close(fd_);
        fail(ErrorKind::Io, path, "cannot stat: " + system_message(err));
    }
    if (!S_ISREG(st.st_mode)) {
        ::close(fd_);
        fail(ErrorKind::Io, path, "not a regular file");
    }
    size_ = std::uint64_t(st.st_size);
}

InputFile::~InputFile() { ::close(fd_); }

std::size_t InputFile::read_some(void* out, std::size_t count) {
    auto* p = static_cast<unsigned char*>(out);
    std::size_t got = 0;
    while (got < count) {
        // At most 1 GiB per call: Linux reads at most 0x7ffff000 bytes at once anyway.
        const std::size_t ask = std::min<std::size_t>(count - got, std::size_t(1) << 30);
        const ssize_t n = ::read(fd_, p + got, ask);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(ErrorKind::Io, path_, "cannot read: " + system_message(errno));
        if (n == 0) break;
        got += std::size_t(n);
    }
    return got;
}

void InputFile::read_exact(void* out, std::size_t count) {
    const std::size_t got = read_some(out, count);
    if (got != count)
        fail(ErrorKind::Format, path_,
             "truncated: the file ended " + std::to_string(count - got) + " bytes early (did it shrink while read?)");
}

std::vector<unsigned char> InputFile::read_exact(std::size_t count) {
    std::vector<unsigned char> bytes(count);
    read_exact(bytes.data(), count);
    return bytes;
}

std::vector<unsigned char> read_file_bytes(const std::string& path, std::uint64_t max_bytes) {
    InputFile file(path);
    if (file.size() > max_bytes)
        fail(ErrorKind::Format, path,
             std::to_string(file.size()) + " bytes, more than the " + std::to_string(max_bytes) +
                 " this reader accepts");
    std::vector<unsigned char> bytes(std::size_t(file.size()));
    bytes.resize(file.read_some(bytes.data(), bytes.size()));  // a file that shrank meanwhile: what is there
    return bytes;
}

}  // namespace vkfuse::io

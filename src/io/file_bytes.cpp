#include "io/file_bytes.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "io/io_error.hpp"

namespace vkfuse::io {
namespace {

// Closes the descriptor on every way out of read_file_bytes.
struct FileDescriptor {
    int fd;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

std::vector<unsigned char> read_file_bytes(const std::string& path) {
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer
    // forever; this way it opens at once and fails the regular-file check. It
    // changes nothing for regular files.
    FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) fail(ErrorKind::Io, path, "cannot open: " + system_message(errno));
    struct stat st {};
    if (::fstat(file.fd, &st) != 0) fail(ErrorKind::Io, path, "cannot stat: " + system_message(errno));
    if (!S_ISREG(st.st_mode)) fail(ErrorKind::Io, path, "not a regular file");

    std::vector<unsigned char> bytes(std::size_t(st.st_size));
    std::size_t got = 0;
    while (got < bytes.size()) {
        ssize_t n = ::read(file.fd, bytes.data() + got, bytes.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(ErrorKind::Io, path, "cannot read: " + system_message(errno));
        if (n == 0) break;  // the file shrank while we read it: keep what is there
        got += std::size_t(n);
    }
    bytes.resize(got);
    return bytes;
}

}  // namespace vkfuse::io

#include "io/atomic_write.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include "io/io_error.hpp"

namespace vkfuse::io {
namespace {

// A hidden name in path's own directory, so the final rename never crosses
// file systems (rename is atomic only within one).
std::string temporary_template(const std::string& path) {
    std::filesystem::path p(path);
    std::string name = "." + p.filename().string() + ".tmp-XXXXXX";
    return p.has_parent_path() ? (p.parent_path() / name).string() : name;
}

// Owns the temporary until it has been renamed into place.
class TemporaryFile {
public:
    explicit TemporaryFile(std::string name) : name_(std::move(name)) {}
    ~TemporaryFile() {
        if (stream_) std::fclose(stream_);
        if (!committed_) ::unlink(name_.c_str());
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    void attach(std::FILE* stream) { stream_ = stream; }
    // Flushes and closes, reporting what fclose alone would hide (a full disk).
    int close() {
        int err = 0;
        if (std::fflush(stream_) != 0 || ::fsync(::fileno(stream_)) != 0) err = errno;
        if (std::fclose(stream_) != 0 && err == 0) err = errno;
        stream_ = nullptr;
        return err;
    }
    void commit() { committed_ = true; }
    const std::string& name() const { return name_; }

private:
    std::string name_;
    std::FILE* stream_ = nullptr;
    bool committed_ = false;
};

}  // namespace

void write_atomically(const std::string& path, const std::function<void(std::FILE*)>& write_body) {
    std::string name = temporary_template(path);
    int fd = ::mkstemp(name.data());
    if (fd < 0) fail(ErrorKind::Io, path, "cannot create a file in its directory: " + system_message(errno));
    TemporaryFile temp(name);
    ::fchmod(fd, 0644);  // mkstemp creates 0600; an image is not a secret
    std::FILE* stream = ::fdopen(fd, "wb");
    if (!stream) {
        int err = errno;
        ::close(fd);
        fail(ErrorKind::Io, path, "cannot write: " + system_message(err));
    }
    temp.attach(stream);
    write_body(stream);
    if (int err = temp.close()) fail(ErrorKind::Io, path, "cannot write: " + system_message(err));
    if (::rename(temp.name().c_str(), path.c_str()) != 0)
        fail(ErrorKind::Io, path, "cannot replace: " + system_message(errno));
    temp.commit();
}

}  // namespace vkfuse::io

#include "io/atomic_write.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <optional>

#include "io/interrupt_cleanup.hpp"
#include "io/io_error.hpp"

namespace vkfuse::io {
namespace {

// A file descriptor closed on every way out.
class Fd {
public:
    explicit Fd(int fd = -1) : fd_(fd) {}
    ~Fd() { reset(); }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    int get() const { return fd_; }
    int release() {
        const int fd = fd_;
        fd_ = -1;
        return fd;
    }
    void reset(int fd = -1) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = fd;
    }

private:
    int fd_;
};

// ".vkfuse-" and 8 random characters: 16 bytes whatever the output's name,
// so a name of up to NAME_MAX bytes can be written.
std::string temporary_name() {
    static constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    unsigned char random[8];
    if (::getrandom(random, sizeof random, GRND_NONBLOCK) != ssize_t(sizeof random)) {
        auto seed = std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                    (std::uint64_t(::getpid()) << 32);
        for (unsigned char& r : random) {
            seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
            r = static_cast<unsigned char>(seed >> 56);
        }
    }
    std::string name = ".vkfuse-";
    for (unsigned char r : random) name += kAlphabet[r % 36];
    return name;
}

// Holds SIGINT, SIGTERM and SIGHUP back while a temporary name is created and
// registered (or released), so the handler never sees a name that is
// registered but not ours (a collision with another process's file) nor a
// file of ours that is not registered yet.
class SignalsHeld {
public:
    SignalsHeld() {
        sigset_t set;
        sigemptyset(&set);
        for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, sig);
        ::pthread_sigmask(SIG_BLOCK, &set, &old_);
    }
    ~SignalsHeld() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
    SignalsHeld(const SignalsHeld&) = delete;
    SignalsHeld& operator=(const SignalsHeld&) = delete;

private:
    sigset_t old_;
};

// path split into the directory to open and the name inside it.
struct Place {
    std::string directory;  // "." for a bare name
    std::string name;
};

Place place_of(const std::string& path) {
    const std::filesystem::path p(path);
    return {p.has_parent_path() ? p.parent_path().string() : ".", p.filename().string()};
}

// What is at path now, following symbolic links (a link to a file: the
// file's mode is the one the user sees).
std::optional<struct stat> existing(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) return st;
    return std::nullopt;
}

// Flushes and closes stream; the first failure (a full disk, EFBIG, EIO on
// fsync) is an Error naming path. sync: fsync before closing (regular files).
void finish(std::FILE*& stream, const std::string& path, bool sync) {
    int err = 0;
    if (std::fflush(stream) != 0) err = errno ? errno : EIO;
    if (err == 0 && std::ferror(stream)) err = EIO;  // a failed fwrite the body did not report
    if (err == 0 && sync && ::fsync(::fileno(stream)) != 0) err = errno;
    if (std::fclose(stream) != 0 && err == 0) err = errno;
    stream = nullptr;
    if (err) fail(ErrorKind::Io, path, "cannot write: " + system_message(err));
}

// A character device or FIFO, written in place. O_NONBLOCK: a FIFO without a
// reader fails at once (ENXIO) instead of waiting forever.
void write_in_place(const std::string& path, const std::function<void(std::FILE*)>& write_body) {
    Fd fd(::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) fail(ErrorKind::Io, path, "cannot open for writing: " + system_message(errno));
    const int flags = ::fcntl(fd.get(), F_GETFL);
    if (flags >= 0) ::fcntl(fd.get(), F_SETFL, flags & ~O_NONBLOCK);
    std::FILE* stream = ::fdopen(fd.get(), "wb");
    if (!stream) fail(ErrorKind::Io, path, "cannot write: " + system_message(errno));
    fd.release();
    try {
        write_body(stream);
    } catch (...) {
        std::fclose(stream);
        throw;
    }
    finish(stream, path, false);
}

// The staged body: an open descriptor and, when it has one, its name (a
// registered one, unlinked again on failure and by the signal handler).
class Staged {
public:
    Staged(int dirfd, const std::string& path) : dirfd_(dirfd), path_(path) {}
    ~Staged() {
        if (stream_) std::fclose(stream_);
        else fd_.reset();
        forget_name(true);
    }
    Staged(const Staged&) = delete;
    Staged& operator=(const Staged&) = delete;

    // An unnamed file in the directory; false where the file system has none.
    bool open_unnamed() {
        const int fd = ::openat(dirfd_, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
        if (fd < 0) {
            const int err = errno;
            // EOPNOTSUPP (the file system), EISDIR (a kernel without O_TMPFILE), EINVAL: stage a named file.
            if (err == EOPNOTSUPP || err == EISDIR || err == EINVAL) return false;
            fail(ErrorKind::Io, path_, "cannot create a file in its directory: " + system_message(err));
        }
        fd_.reset(fd);
        // The link at the end goes through /proc/self/fd; without /proc
        // (a bare chroot) a named file is the only way.
        if (::access(proc_link().c_str(), F_OK) != 0) {
            fd_.reset();
            return false;
        }
        return true;
    }

    void open_named() {
        for (int attempt = 0; attempt < 100; ++attempt) {
            std::string name = temporary_name();
            int fd, err;
            {
                SignalsHeld held;
                fd = ::openat(dirfd_, name.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC | O_NOCTTY, 0666);
                err = errno;
                if (fd >= 0) slot_ = register_temporary(dirfd_, name);
            }
            if (fd >= 0) {
                fd_.reset(fd);
                name_ = std::move(name);
                return;
            }
            if (err != EEXIST) fail(ErrorKind::Io, path_, "cannot create a file in its directory: " + system_message(err));
        }
        fail(ErrorKind::Io, path_, "cannot create a file in its directory: no free temporary name");
    }

    int fd() const { return fd_.get(); }

    std::FILE* stream() {
        stream_ = ::fdopen(fd_.get(), "wb");
        if (!stream_) fail(ErrorKind::Io, path_, "cannot write: " + system_message(errno));
        fd_.release();
        return stream_;
    }

    // Flushed, fsynced and closed; then given a name if it has none yet.
    void close_and_name() {
        // An unnamed file must be linked while its descriptor is open.
        const bool unnamed = name_.empty();
        int err = 0;
        if (std::fflush(stream_) != 0) err = errno ? errno : EIO;
        if (err == 0 && std::ferror(stream_)) err = EIO;
        if (err == 0 && ::fsync(::fileno(stream_)) != 0) err = errno;
        if (err) fail(ErrorKind::Io, path_, "cannot write: " + system_message(err));
        if (unnamed) link_unnamed(::fileno(stream_));
        const int closed = std::fclose(stream_);
        stream_ = nullptr;
        if (closed != 0) fail(ErrorKind::Io, path_, "cannot write: " + system_message(errno));
    }

    void rename_to(const std::string& final_name) {
        SignalsHeld held;  // renamed and released as one step for the handler
        if (::renameat(dirfd_, name_.c_str(), dirfd_, final_name.c_str()) != 0)
            fail(ErrorKind::Io, path_, "cannot replace: " + system_message(errno));
        forget_name(false);
    }

private:
    std::string proc_link() const { return "/proc/self/fd/" + std::to_string(fd_.get()); }

    void link_unnamed(int fd) {
        const std::string source = "/proc/self/fd/" + std::to_string(fd);
        for (int attempt = 0; attempt < 100; ++attempt) {
            std::string name = temporary_name();
            int linked, err;
            {
                SignalsHeld held;
                linked = ::linkat(AT_FDCWD, source.c_str(), dirfd_, name.c_str(), AT_SYMLINK_FOLLOW);
                err = errno;
                if (linked == 0) slot_ = register_temporary(dirfd_, name);
            }
            if (linked == 0) {
                name_ = std::move(name);
                return;
            }
            if (err != EEXIST) fail(ErrorKind::Io, path_, "cannot create a file in its directory: " + system_message(err));
        }
        fail(ErrorKind::Io, path_, "cannot create a file in its directory: no free temporary name");
    }

    void forget_name(bool unlink) {
        if (name_.empty()) return;
        SignalsHeld held;
        if (unlink) ::unlinkat(dirfd_, name_.c_str(), 0);
        release_temporary(slot_);
        name_.clear();
        slot_ = -1;
    }

    int dirfd_;
    const std::string& path_;
    Fd fd_;
    std::FILE* stream_ = nullptr;
    std::string name_;
    int slot_ = -1;
};

// The replaced file's owner, group and permission bits, as far as this
// process may set them. fchown first: it clears set-user-ID bits.
void keep_attributes(int fd, const struct stat& old) {
    const bool owned = ::fchown(fd, old.st_uid, old.st_gid) == 0;
    const bool grouped = owned || ::fchown(fd, uid_t(-1), old.st_gid) == 0;
    // Set-ID bits only on a file that kept its owner and group: never on one
    // that now belongs to someone else.
    const mode_t mode = old.st_mode & (owned && grouped ? 07777 : 01777);
    ::fchmod(fd, mode);
}

}  // namespace

void write_all(std::FILE* out, const void* data, std::size_t size, const std::string& path) {
    if (size == 0) return;
    errno = 0;
    if (std::fwrite(data, 1, size, out) != size)
        fail(ErrorKind::Io, path, "cannot write: " + system_message(errno ? errno : EIO));
}

void write_atomically(const std::string& path, const std::function<void(std::FILE*)>& write_body, Staging staging) {
    const std::optional<struct stat> old = existing(path);
    if (old && S_ISDIR(old->st_mode)) fail(ErrorKind::Io, path, "cannot replace: " + system_message(EISDIR));
    if (old && (S_ISCHR(old->st_mode) || S_ISFIFO(old->st_mode))) return write_in_place(path, write_body);
    if (old && !S_ISREG(old->st_mode)) fail(ErrorKind::Io, path, "cannot replace: not a regular file");

    const Place place = place_of(path);
    Fd dir(::open(place.directory.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
    if (dir.get() < 0) fail(ErrorKind::Io, path, "cannot create a file in its directory: " + system_message(errno));

    Staged staged(dir.get(), path);
    if (staging == Staging::Named || !staged.open_unnamed()) staged.open_named();
    if (old) keep_attributes(staged.fd(), *old);
    write_body(staged.stream());
    staged.close_and_name();
    staged.rename_to(place.name);
    // The rename is durable once the directory is: best effort, the data is.
    Fd sync_dir(::open(place.directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (sync_dir.get() >= 0) ::fsync(sync_dir.get());
}

}  // namespace vkfuse::io

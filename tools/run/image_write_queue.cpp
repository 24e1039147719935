#include "run/image_write_queue.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "io/png.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::cli {
namespace {

std::size_t bytes_of(const std::shared_ptr<const Image>& image) {
    return image ? image->data.size() * sizeof(float) : 0;
}

[[noreturn]] void fail_io(const std::string& path, const std::string& what, int err) {
    throw Error(ErrorKind::Io, path + ": " + what + ": " + std::strerror(err));
}

// A new file (never one planted under its name), encoded for speed; removed
// again if it cannot be written whole.
void write_new_png(const std::string& path, const Image& image) {
    io::check_finite(image, path);
    const int fd = create_new_file(path);
    std::FILE* out = ::fdopen(fd, "wb");
    if (!out) {
        const int err = errno;
        ::close(fd);
        ::unlink(path.c_str());
        fail_io(path, "cannot write", err);
    }
    try {
        io::write_png(out, image, path, io::PngSpeed::Fast);
        if (std::fflush(out) != 0 || std::ferror(out)) fail_io(path, "write failed", errno ? errno : EIO);
    } catch (...) {
        std::fclose(out);
        ::unlink(path.c_str());
        throw;
    }
    if (std::fclose(out) != 0) {
        const int err = errno;
        ::unlink(path.c_str());
        fail_io(path, "write failed", err);
    }
}

}  // namespace

int create_new_file(const std::string& path) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) fail_io(path, "cannot create", errno);
    return fd;
}

void add_file_name(const std::string& earlier, const std::string& path) {
    if (::link(earlier.c_str(), path.c_str()) == 0) return;
    const int err = errno;
    if (err != EXDEV && err != EPERM && err != EMLINK && err != EOPNOTSUPP) fail_io(path, "cannot create", err);
    std::error_code ec;  // copy_file refuses an existing target: path stays new
    std::filesystem::copy_file(earlier, path, std::filesystem::copy_options::none, ec);
    if (ec) {
        std::filesystem::remove(path);
        throw Error(ErrorKind::Io, path + ": cannot copy " + earlier + ": " + ec.message());
    }
}

ImageWriteQueue::ImageWriteQueue(std::size_t max_pending_bytes)
    : max_pending_bytes_(max_pending_bytes), thread_([this] { work(); }) {}

ImageWriteQueue::~ImageWriteQueue() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void ImageWriteQueue::rethrow_error_locked() {
    if (error_) std::rethrow_exception(error_);
}

void ImageWriteQueue::push_png(std::string path, std::shared_ptr<const Image> image) {
    push({std::move(path), std::move(image), {}});
}

void ImageWriteQueue::push_link(std::string path, std::string earlier) {
    push({std::move(path), nullptr, std::move(earlier)});
}

void ImageWriteQueue::push(Job job) {
    const std::size_t bytes = bytes_of(job.image);
    std::unique_lock lock(mutex_);
    // One image always fits, whatever its size, or nothing would ever move.
    changed_.wait(lock, [&] { return error_ || jobs_.empty() || pending_bytes_ + bytes <= max_pending_bytes_; });
    rethrow_error_locked();
    pending_bytes_ += bytes;
    jobs_.push_back(std::move(job));
    lock.unlock();
    changed_.notify_all();
}

void ImageWriteQueue::drain() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return error_ || (jobs_.empty() && !busy_); });
    rethrow_error_locked();
}

void ImageWriteQueue::work() {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
        if (stop_) return;
        Job job = std::move(jobs_.front());
        jobs_.pop_front();
        busy_ = true;
        lock.unlock();
        std::exception_ptr failure;
        try {
            if (job.image) write_new_png(job.path, *job.image);
            else add_file_name(job.earlier, job.path);
        } catch (...) {
            failure = std::current_exception();
        }
        lock.lock();
        busy_ = false;
        pending_bytes_ -= bytes_of(job.image);
        if (failure && !error_) error_ = failure;
        changed_.notify_all();
    }
}

}  // namespace vkfuse::cli

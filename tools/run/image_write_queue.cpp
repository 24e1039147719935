#include "run/image_write_queue.hpp"

#include "vkfuse/core/io.hpp"

namespace vkfuse::cli {
namespace {

std::size_t bytes_of(const Image& image) { return image.data.size() * sizeof(float); }

}  // namespace

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

void ImageWriteQueue::push(std::string path, Image image) {
    const std::size_t bytes = bytes_of(image);
    std::unique_lock lock(mutex_);
    // One image always fits, whatever its size, or nothing would ever move.
    changed_.wait(lock, [&] { return error_ || jobs_.empty() || pending_bytes_ + bytes <= max_pending_bytes_; });
    rethrow_error_locked();
    pending_bytes_ += bytes;
    jobs_.push_back({std::move(path), std::move(image)});
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
            io::write_image(job.path, job.image);
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

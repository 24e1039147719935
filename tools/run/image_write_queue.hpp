// image_write_queue.hpp - image files written by a thread of their own.
//
// Encoding a PNG takes longer than fusing it on a fast device; done on the
// rig's loop thread it holds every cycle back. The queue takes each image
// (copied: a rig's fused image lives only until its next cycle), writes the
// images in order on one background thread, and bounds what waits in memory:
// push() blocks while the images waiting exceed the byte budget, so a slow disk
// slows the loop down instead of growing without limit.
#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

#include "vkfuse/core/image.hpp"

namespace vkfuse::cli {

class ImageWriteQueue {
public:
    explicit ImageWriteQueue(std::size_t max_pending_bytes);
    // Stops at once: images still waiting are not written (an abandoned run
    // discards its output directory anyway).
    ~ImageWriteQueue();
    ImageWriteQueue(const ImageWriteQueue&) = delete;
    ImageWriteQueue& operator=(const ImageWriteQueue&) = delete;

    // Queues path <- image (io::write_image). Rethrows the first error any
    // earlier write met, so a full disk fails the run at the next cycle.
    void push(std::string path, Image image);
    // Waits until every queued image is written; rethrows the first error.
    void drain();

private:
    struct Job {
        std::string path;
        Image image;
    };
    void work();
    void rethrow_error_locked();

    std::size_t max_pending_bytes_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Job> jobs_;
    std::size_t pending_bytes_ = 0;
    bool busy_ = false;  // the thread is writing a job it has taken off the queue
    bool stop_ = false;
    std::exception_ptr error_;
    std::thread thread_;  // last: started once everything above exists
};

}  // namespace vkfuse::cli

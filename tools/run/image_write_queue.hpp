// image_write_queue.hpp - a run's fused PNGs, written by a thread of their own.
//
// Encoding a PNG takes longer than fusing it on a fast device; done on the
// rig's loop thread it holds every cycle back. The queue takes each image
// (shared, so the caller may keep it: a rig's own fused image lives only until
// its next cycle, so callers hand over a copy), writes the files in order on
// one background thread, and bounds what waits in memory: push_png() blocks
// while the images waiting exceed the byte budget, so a slow disk slows the
// loop down instead of growing without limit.
//
// The files are new names in a run's staging directory, which appears under
// its final name only when the run ends well: each file is created once
// (O_EXCL, never through a planted link) and not synced on its own. The PNGs
// are encoded for speed (zlib level 1, one filter): the same pixels as the
// smallest encoding, written every cycle. A file whose image an earlier file
// already holds bit for bit is a second name for it (a hard link; a copy of
// its bytes where the file system has no links), not a second encoding.
#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
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

    // Queues a new PNG file at path holding image (finite, 1 or 3 channels).
    // Rethrows the first error any earlier job met, so a full disk fails the
    // run at the next cycle.
    void push_png(std::string path, std::shared_ptr<const Image> image);
    // Queues path as a new name for the file earlier, queued before it.
    void push_link(std::string path, std::string earlier);
    // Waits until every queued file is written; rethrows the first error.
    void drain();

private:
    struct Job {
        std::string path;
        std::shared_ptr<const Image> image;  // a PNG to encode, or
        std::string earlier;                 // the file path is another name for
    };
    void push(Job job);
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

// A new file at path, open for writing (O_EXCL, O_NOFOLLOW: nothing planted
// under its name is opened). Throws Error(Io) naming path.
int create_new_file(const std::string& path);

// path as a new name for the existing file earlier: a hard link, or where the
// file system refuses one (no links, another device, too many) a new file
// holding earlier's bytes. Throws Error(Io) naming path.
void add_file_name(const std::string& earlier, const std::string& path);

}  // namespace vkfuse::cli

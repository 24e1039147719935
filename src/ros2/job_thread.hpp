// job_thread.hpp - one thread that runs the jobs handed to it, in order, so
// that whoever hands one over goes on at once (a capture thread publishing
// its sensor's background: megabytes to serialize, which would otherwise
// hold its first cycles up).
#pragma once
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace vkfuse::ros2 {

class JobThread {
public:
    JobThread() = default;
    ~JobThread() { finish(); }
    JobThread(const JobThread&) = delete;
    JobThread& operator=(const JobThread&) = delete;

    // Queues job; the thread starts with the first. A job must not throw.
    void push(std::function<void()> job) {
        std::lock_guard lock(mutex_);
        jobs_.push_back(std::move(job));
        if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
        changed_.notify_all();
    }

    // Runs every job queued, then ends the thread; called once no one
    // pushes any more (the destructor does).
    void finish() {
        {
            std::lock_guard lock(mutex_);
            if (!thread_.joinable()) return;
            finishing_ = true;
            changed_.notify_all();
        }
        thread_.join();
    }

private:
    void run() {
        std::unique_lock lock(mutex_);
        for (;;) {
            changed_.wait(lock, [&] { return finishing_ || !jobs_.empty(); });
            if (jobs_.empty()) return;  // finishing, nothing left
            std::function<void()> job = std::move(jobs_.front());
            jobs_.pop_front();
            lock.unlock();
            job();
            lock.lock();
        }
    }

    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<std::function<void()>> jobs_;
    bool finishing_ = false;
    std::thread thread_;
};

}  // namespace vkfuse::ros2

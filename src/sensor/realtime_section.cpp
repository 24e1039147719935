// RealtimeSection (sensor/realtime_section.hpp), through pthread_setschedparam
// on the calling thread.
#include "sensor/realtime_section.hpp"

#include <pthread.h>
#include <sched.h>

#include <cstring>

namespace vkfuse::sensor {

std::string realtime_refusal(int priority) {
    if (priority < 1 || priority > 99) return "priority " + std::to_string(priority) + " is outside 1..99";
    return RealtimeSection(priority).refusal();
}

RealtimeSection::RealtimeSection(int priority) {
    if (priority <= 0) return;
    sched_param own{};
    if (const int e = pthread_getschedparam(pthread_self(), &policy_, &own)) {
        refusal_ = std::strerror(e);
        return;
    }
    priority_ = own.sched_priority;
    // A thread already real-time at this priority or above keeps its own.
    if ((policy_ == SCHED_FIFO || policy_ == SCHED_RR) && priority_ >= priority) return;
    sched_param wanted{};
    wanted.sched_priority = priority;
    if (const int e = pthread_setschedparam(pthread_self(), SCHED_FIFO, &wanted))
        refusal_ = std::strerror(e);
    else
        raised_ = true;
}

RealtimeSection::~RealtimeSection() {
    if (!raised_) return;
    sched_param own{};
    own.sched_priority = priority_;
    pthread_setschedparam(pthread_self(), policy_, &own);
}

}  // namespace vkfuse::sensor

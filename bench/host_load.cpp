#include "host_load.hpp"

#include <fstream>

namespace vkfuse::bench {

double load_average() {
    std::ifstream in("/proc/loadavg");
    double one_minute = -1;
    if (!(in >> one_minute)) return -1;
    return one_minute;
}

}  // namespace vkfuse::bench

// A bad command line: main() prints the message on one line and exits 2.
#pragma once
#include <stdexcept>
#include <string>

namespace vkfuse::bench {

class UsageError : public std::runtime_error {
public:
    explicit UsageError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vkfuse::bench

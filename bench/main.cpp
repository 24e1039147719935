// vkfuse-bench: run time against error, side by side with the Python peers.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "driver.hpp"
#include "options.hpp"
#include "usage_error.hpp"

int main(int argc, char** argv) {
    using namespace vkfuse::bench;
    try {
        const Options options = parse_options(std::vector<std::string>(argv + 1, argv + argc));
        if (options.help) {
            std::fputs(help_text().c_str(), stdout);
            return 0;
        }
        return run_bench(options);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "vkfuse-bench: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkfuse-bench: %s\n", e.what());
        return 1;
    }
}

// vkfuse-bench: run time against error, side by side with the Python peers.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "driver.hpp"
#include "io/interrupt_cleanup.hpp"
#include "options.hpp"

int main(int argc, char** argv) {
    using namespace vkfuse::bench;
    try {
        const Options options = parse_options(std::vector<std::string>(argv + 1, argv + argc));
        if (options.help) {
            std::fputs(help_text().c_str(), stdout);
            return 0;
        }
        // A SIGINT/SIGTERM while --json/--plot are written leaves no temporary.
        vkfuse::io::install_interrupt_cleanup();
        const int status = run_bench(options);
        // The table and summary go to stdout unchecked line by line; its error
        // flag is sticky, so one check here catches a full disk or a closed pipe.
        errno = 0;
        if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
            std::fprintf(stderr, "vkfuse-bench: stdout: cannot write: %s\n",
                         std::strerror(errno ? errno : EIO));
            return 1;
        }
        return status;
    } catch (const UsageError& e) {
        std::fprintf(stderr, "vkfuse-bench: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkfuse-bench: %s\n", e.what());
        return 1;
    }
}

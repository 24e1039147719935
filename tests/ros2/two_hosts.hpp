// Two hosts of a rig on this machine: network namespaces joined by a veth
// pair, each with its own address, so DDS discovers and talks across a real
// link (and packets on it can be dropped). Needs root (CI runs as root).
#pragma once
#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace vkfuse::test::ros2 {

class TwoHosts {
public:
    // Why two hosts cannot be made here (not root, no `ip netns`), or nullopt.
    static std::optional<std::string> unavailable();
    // Namespaces named after the pid; throws std::runtime_error with the
    // command that failed.
    TwoHosts();
    ~TwoHosts();  // removes both namespaces (and the pair with them)
    TwoHosts(const TwoHosts&) = delete;
    TwoHosts& operator=(const TwoHosts&) = delete;

    // Drops `percent` % of the UDP packets host ('a' or 'b') receives, at
    // random (nftables' numgen: this kernel has no netem).
    void drop_udp(char host, int percent);
    // Starts vkfuse with args on host, stdout and stderr to the files named.
    pid_t start(char host, const std::vector<std::string>& args, const std::string& out_path,
                const std::string& err_path) const;

private:
    std::string name(char host) const;
    std::string a_, b_;
};

// Waits for pid (at most timeout_s; then kills it): its exit status, or 128 + signal.
int wait_exit(pid_t pid, double timeout_s);

}  // namespace vkfuse::test::ros2

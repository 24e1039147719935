#include "two_hosts.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace vkfuse::test::ros2 {
namespace {

int shell(const std::string& command) { return std::system((command + " >/dev/null 2>&1").c_str()); }

void must(const std::string& command) {
    if (shell(command) != 0) throw std::runtime_error("two hosts: `" + command + "` failed");
}

}  // namespace

std::optional<std::string> TwoHosts::unavailable() {
    if (geteuid() != 0) return "two hosts need root (network namespaces); not root here";
    const std::string probe = "vkfuse_probe_" + std::to_string(getpid());
    if (shell("ip netns add " + probe) != 0) return "`ip netns add` failed (no iproute2, or no namespaces here)";
    shell("ip netns del " + probe);
    if (shell("command -v nft") != 0) return "no nft (apt-get install nftables)";
    return std::nullopt;
}

TwoHosts::TwoHosts() {
    const std::string id = std::to_string(getpid());
    a_ = "vkfa" + id;
    b_ = "vkfb" + id;
    const std::string subnet = "10." + std::to_string(getpid() % 200 + 20) + ".0.";
    must("ip netns add " + a_);
    must("ip netns add " + b_);
    must("ip link add va" + id + " netns " + a_ + " type veth peer name vb" + id + " netns " + b_);
    for (const auto& [ns, dev, address] : {std::tuple{a_, "va" + id, subnet + "1"}, {b_, "vb" + id, subnet + "2"}}) {
        must("ip -n " + ns + " link set lo up");
        must("ip -n " + ns + " addr add " + address + "/24 dev " + dev);
        must("ip -n " + ns + " link set " + dev + " up multicast on");
        // DDS discovers over multicast: the pair is each host's only way out.
        must("ip -n " + ns + " route add 224.0.0.0/4 dev " + dev);
    }
}

TwoHosts::~TwoHosts() {
    shell("ip netns del " + a_);
    shell("ip netns del " + b_);
}

std::string TwoHosts::name(char host) const { return host == 'a' ? a_ : b_; }

void TwoHosts::drop_udp(char host, int percent) {
    const std::string ns = "ip netns exec " + name(host) + " nft ";
    must(ns + "add table inet vkfuse_loss");
    must(ns + "'add chain inet vkfuse_loss input { type filter hook input priority 0; }'");
    must(ns + "add rule inet vkfuse_loss input meta l4proto udp numgen random mod 100 '<' " + std::to_string(percent) +
         " drop");
}

pid_t TwoHosts::start(char host, const std::vector<std::string>& args, const std::string& out_path,
                      const std::string& err_path) const {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> words{"ip", "netns", "exec", name(host), VKFUSE_CLI};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, "ip", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("two hosts: cannot start ip netns exec");
    return pid;
}

int wait_exit(pid_t pid, double timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() >= deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace vkfuse::test::ros2

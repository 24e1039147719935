// staged_directory.hpp - an output directory that appears whole or not at all.
//
// `vkfuse run --out DIR` and `--record DIR` write into a fresh hidden sibling
// of DIR (".vkfuse-partial-XXXXXX" in DIR's parent) and publish it under DIR's
// name only when the command succeeds. So a run that fails leaves every
// existing file as it was, two runs never mix their files in one directory,
// and nothing a run writes can land on a file (or a planted symbolic link)
// that was already there.
#pragma once
#include <functional>
#include <string>

namespace vkfuse::cli {

class StagedDirectory {
public:
    // What may already be at the target.
    struct Policy {
        std::string option;  // "--out", for messages
        // Replace an existing non-empty directory whole on publish(). Only a
        // directory whose top-level entries all satisfy `ours` (names this
        // command writes) is replaced: a mistyped path never costs a user
        // their files.
        bool replace = false;
        std::function<bool(const std::string& entry)> ours;
        std::string replace_option;  // "--replace", named in the refusal
    };

    // Checks target (missing, an empty directory, or replaceable under
    // policy; never a symbolic link) and creates the staging directory with
    // mode 0777 less the umask. Throws Error(InvalidArgument / Io), one line
    // naming target, before anything is created.
    StagedDirectory(std::string target, Policy policy);
    // Removes the staging directory and everything in it unless published or kept.
    ~StagedDirectory();
    StagedDirectory(const StagedDirectory&) = delete;
    StagedDirectory& operator=(const StagedDirectory&) = delete;

    // Where to write now.
    const std::string& path() const { return staging_; }
    const std::string& target() const { return target_; }
    // target normalised ("out/" and "./out" are "out"): the name published.
    const std::string& where() const { return where_; }

    // Moves the staging directory to target in one rename (an exchange when
    // replacing, then the old directory is removed). If target was filled by
    // someone else meanwhile, keeps the staging directory and throws
    // Error(Io) saying where this command's results are.
    void publish();

private:
    std::string target_;  // as the user wrote it, for messages
    std::string where_;   // the same directory, normalised: what the system calls use
    std::string staging_;
    Policy policy_;
    bool done_ = false;
};

}  // namespace vkfuse::cli

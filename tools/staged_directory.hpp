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
#include <memory>
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

// One output file that appears whole or not at all, never over a file that
// is there: written at path(), inside a fresh hidden directory beside target
// (".vkfuse-partial-XXXXXXXX"), and moved to target by publish() in one
// rename that refuses to replace anything (`vkfuse run --record rig.mcap`).
class StagedFile {
public:
    // Throws Error(InvalidArgument / Io), one line naming target, when it
    // exists (even as a dangling link) or cannot be staged beside.
    StagedFile(std::string target, std::string option);
    ~StagedFile();
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;

    const std::string& path() const { return path_; }
    const std::string& target() const { return target_; }
    // Throws Error(Io) saying where the file is when target appeared meanwhile.
    void publish();

private:
    std::string target_, option_, staging_, path_;
    bool done_ = false;
};

// A dataset's output in the form its name asks for (is_mcap_path): one MCAP
// file (StagedFile) or a directory (StagedDirectory, never replacing).
class StagedDataset {
public:
    StagedDataset(const std::string& target, const std::string& option);
    ~StagedDataset();
    const std::string& path() const;    // where to write now
    const std::string& target() const;  // as the user wrote it
    // The normalised directory, for comparing with another output ("" for a file).
    std::string where() const;
    void publish();

private:
    std::unique_ptr<StagedDirectory> directory_;
    std::unique_ptr<StagedFile> file_;
};

}  // namespace vkfuse::cli

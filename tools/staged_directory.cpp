#include "staged_directory.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::cli {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(ErrorKind kind, const std::string& message) { throw Error(kind, message); }

std::string errno_text(int err) { return std::strerror(err); }

// A new, empty directory with a random name in parent, created by mkdir so the
// kernel applies the umask (mkdtemp would force 0700).
std::string make_unique_directory(const fs::path& parent, const std::string& prefix, const std::string& about) {
    std::random_device entropy;
    static constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name = prefix;
        for (int i = 0; i < 8; ++i) name += kAlphabet[entropy() % (sizeof kAlphabet - 1)];
        const std::string path = (parent / name).string();
        if (::mkdir(path.c_str(), 0777) == 0) return path;
        if (errno != EEXIST) fail(ErrorKind::Io, about + ": cannot create a directory beside it: " + errno_text(errno));
    }
    fail(ErrorKind::Io, about + ": cannot create a directory beside it: too many names taken");
}

bool is_empty_directory(const std::string& path) {
    std::error_code ec;
    return fs::is_empty(path, ec) && !ec;
}

// Removes what this command created; never follows a symbolic link out.
void remove_tree(const std::string& path) {
    std::error_code ec;
    fs::remove_all(path, ec);
}

fs::path parent_of(const std::string& target) {
    fs::path p = fs::path(target).parent_path();
    return p.empty() ? fs::path(".") : p;
}

}  // namespace

StagedDirectory::StagedDirectory(std::string target, Policy policy)
    : target_(std::move(target)), policy_(std::move(policy)) {
    const std::string about = policy_.option + " " + target_;
    if (target_.empty()) fail(ErrorKind::InvalidArgument, policy_.option + ": empty path");
    // "out/", "./out" and "a/../out" name the directory "out": its staging
    // sibling goes beside it, never inside. ".", ".." and "/" name no new
    // directory a run could publish.
    fs::path normal = fs::path(target_).lexically_normal();
    if (!normal.has_filename()) normal = normal.parent_path();
    if (normal.empty() || !normal.has_filename() || normal.filename() == "." || normal.filename() == "..")
        fail(ErrorKind::InvalidArgument, about + ": name a directory of its own (not . or .. or /)");
    where_ = normal.string();
    struct stat st {};
    if (::lstat(where_.c_str(), &st) == 0) {
        if (S_ISLNK(st.st_mode))
            fail(ErrorKind::InvalidArgument, about + ": is a symbolic link; name the directory itself");
        if (!S_ISDIR(st.st_mode)) fail(ErrorKind::InvalidArgument, about + ": exists and is not a directory");
        if (!is_empty_directory(where_)) {
            if (!policy_.replace)
                fail(ErrorKind::InvalidArgument,
                     about + ": exists and is not empty" +
                         (policy_.replace_option.empty() ? std::string(" (name a new directory)")
                                                         : " (name a new one, or add " + policy_.replace_option +
                                                               " to replace it once this run succeeds)"));
            std::error_code ec;
            for (const fs::directory_entry& e : fs::directory_iterator(where_, ec)) {
                const std::string name = e.path().filename().string();
                if (!policy_.ours || !policy_.ours(name))
                    fail(ErrorKind::InvalidArgument, about + ": holds " + name +
                                                         ", which this command does not write; refusing to replace it");
            }
            if (ec) fail(ErrorKind::Io, about + ": cannot list: " + ec.message());
        }
    } else if (errno != ENOENT) {
        fail(ErrorKind::Io, about + ": " + errno_text(errno));
    }
    const fs::path parent = parent_of(where_);
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) fail(ErrorKind::Io, about + ": cannot create " + parent.string() + ": " + ec.message());
    staging_ = make_unique_directory(parent, ".vkfuse-partial-", about);
}

StagedDirectory::~StagedDirectory() {
    if (!done_) remove_tree(staging_);
}

void StagedDirectory::publish() {
    const std::string about = policy_.option + " " + target_;
    // rename() moves a directory onto a missing name or an empty directory in
    // one step; a non-empty target makes it fail with ENOTEMPTY/EEXIST.
    if (::rename(staging_.c_str(), where_.c_str()) == 0) {
        done_ = true;
        return;
    }
    int err = errno;
    if ((err == ENOTEMPTY || err == EEXIST) && policy_.replace) {
        // Swap atomically where the kernel and file system can, so the target
        // name always holds one complete run; else move the old one aside first.
        if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, where_.c_str(), RENAME_EXCHANGE) == 0) {
            done_ = true;
            remove_tree(staging_);  // now the replaced run
            return;
        }
        const std::string old = make_unique_directory(parent_of(where_), ".vkfuse-replaced-", about);
        if (::rename(where_.c_str(), old.c_str()) != 0) {
            err = errno;
            ::rmdir(old.c_str());
        } else if (::rename(staging_.c_str(), where_.c_str()) != 0) {
            err = errno;
            ::rename(old.c_str(), where_.c_str());  // put the previous run back
        } else {
            done_ = true;
            remove_tree(old);
            return;
        }
    }
    done_ = true;  // keep this command's results where they are
    fail(ErrorKind::Io, about + ": cannot put the results in place (" + errno_text(err) +
                            "); they are in " + staging_);
}

StagedFile::StagedFile(std::string target, std::string option) : target_(std::move(target)), option_(std::move(option)) {
    const std::string about = option_ + " " + target_;
    const fs::path p(target_);
    if (target_.empty() || !p.has_filename() || p.filename() == "." || p.filename() == "..")
        fail(ErrorKind::InvalidArgument, about + ": name a file");
    struct stat st {};
    if (::lstat(target_.c_str(), &st) == 0) fail(ErrorKind::InvalidArgument, about + ": exists (name a new file)");
    if (errno != ENOENT) fail(ErrorKind::Io, about + ": " + errno_text(errno));
    staging_ = make_unique_directory(parent_of(target_), ".vkfuse-partial-", about);
    path_ = (fs::path(staging_) / p.filename()).string();
}

StagedFile::~StagedFile() {
    if (!done_) remove_tree(staging_);
}

void StagedFile::publish() {
    const std::string about = option_ + " " + target_;
    if (::renameat2(AT_FDCWD, path_.c_str(), AT_FDCWD, target_.c_str(), RENAME_NOREPLACE) != 0) {
        int err = errno;
        // A file system without renameat2's flags: a hard link never replaces either.
        if (err == EINVAL || err == ENOSYS) {
            if (::link(path_.c_str(), target_.c_str()) == 0) {
                ::unlink(path_.c_str());
                err = 0;
            } else {
                err = errno;
            }
        }
        if (err != 0) {
            done_ = true;  // keep this command's file where it is
            fail(ErrorKind::Io, about + ": cannot put the file in place (" + errno_text(err) + "); it is " + path_);
        }
    }
    done_ = true;
    ::rmdir(staging_.c_str());
}

StagedDataset::StagedDataset(const std::string& target, const std::string& option) {
    if (is_mcap_path(target))
        file_ = std::make_unique<StagedFile>(target, option);
    else
        directory_ = std::make_unique<StagedDirectory>(target, StagedDirectory::Policy{option, false, nullptr, ""});
}

StagedDataset::~StagedDataset() = default;

const std::string& StagedDataset::path() const { return file_ ? file_->path() : directory_->path(); }
const std::string& StagedDataset::target() const { return file_ ? file_->target() : directory_->target(); }
std::string StagedDataset::where() const { return directory_ ? directory_->where() : std::string(); }

void StagedDataset::publish() {
    if (file_) file_->publish();
    if (directory_) directory_->publish();
}

}  // namespace vkfuse::cli

// A private temporary directory, removed with everything in it when done.
#pragma once
#include <filesystem>

namespace vkfuse::bench {

class TempDir {
public:
    TempDir();  // under $TMPDIR (or /tmp); throws std::runtime_error on failure
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace vkfuse::bench

#include "temp_dir.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <system_error>

namespace vkfuse::bench {

TempDir::TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "vkfuse-bench-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary directory in " + pattern);
    path_ = pattern;
}

TempDir::~TempDir() {
    std::error_code ignored;  // nothing useful to do about a failed cleanup in a destructor
    std::filesystem::remove_all(path_, ignored);
}

}  // namespace vkfuse::bench

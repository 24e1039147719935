// io/file_bytes.hpp - reading files whose sizes are checked before any byte is
// read, with errors that name the file.
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vkfuse::io {

// An open regular file. A reader asks for exactly the bytes a checked header
// promises; nothing here reads "the rest of the file", so a 1 TB (sparse)
// file costs what its header says, not 1 TB.
class InputFile {
public:
    // Throws Error(Io) "path: cannot open: No such file or directory",
    // "path: not a regular file", ... (a FIFO fails at once, never blocks).
    explicit InputFile(const std::string& path);
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    const std::string& path() const { return path_; }
    std::uint64_t size() const { return size_; }  // st_size when opened

    // Up to count bytes from the current position into out; fewer only at the
    // end of the file. Throws Error(Io) on a read error.
    std::size_t read_some(void* out, std::size_t count);
    // Exactly count bytes, or Error(Format) "path: truncated ..." (the file
    // shrank since it was sized) / Error(Io).
    void read_exact(void* out, std::size_t count);
    std::vector<unsigned char> read_exact(std::size_t count);

private:
    std::string path_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
};

// The contents of the regular file at path, refused with Error(Format)
// "path: N bytes, more than the M this reader accepts" before anything is
// read when the file is larger than max_bytes. Throws Error(Io) as InputFile.
std::vector<unsigned char> read_file_bytes(const std::string& path,
                                           std::uint64_t max_bytes = std::numeric_limits<std::uint64_t>::max());

}  // namespace vkfuse::io

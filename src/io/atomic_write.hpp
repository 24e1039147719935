// io/atomic_write.hpp - write a whole file or nothing.
#pragma once
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

namespace vkfuse::io {

// How the body is staged before it takes path's name. Tests pick Named to
// exercise the fallback; everything else leaves the default.
enum class Staging {
    Auto,   // an unnamed O_TMPFILE file where the file system has them, else Named
    Named,  // a short hidden name in path's directory (".vkfuse-XXXXXXXX")
};

// Writes path whole or not at all. write_body fills a stream; the result is
// flushed, checked (a full disk, a file-size limit), fsynced and only then
// given path's name with one rename, so path is never partially written and
// a failure leaves whatever was there untouched. write_body reports its own
// failures by throwing; a stream error it did not notice is caught here.
//
// - The body goes to an unnamed file (O_TMPFILE) linked in just before the
//   rename, or where the file system lacks those to a hidden name of 16
//   bytes: any output name the file system accepts works (up to 255 bytes),
//   and an interrupted process leaves nothing behind (see
//   interrupt_cleanup.hpp for the named case).
// - A new file gets 0666 & ~umask (like open(2)); a replaced regular file
//   keeps its permission bits and, where the process may set them, its
//   owner and group.
// - An existing character device or FIFO (/dev/null, /dev/full, a pipe) is
//   written in place: there is no file to keep whole. A directory or any
//   other kind of file is refused.
//
// Errors are Error(Io) (or what write_body throws) naming path.
void write_atomically(const std::string& path, const std::function<void(std::FILE*)>& write_body,
                      Staging staging = Staging::Auto);

// fwrite of the whole range, or Error(Io) "path: cannot write: <errno text>".
void write_all(std::FILE* out, const void* data, std::size_t size, const std::string& path);
inline void write_all(std::FILE* out, std::string_view text, const std::string& path) {
    write_all(out, text.data(), text.size(), path);
}

}  // namespace vkfuse::io

// An MCAP recording of arbitrary bytes through everything `vkfuse run
// --replay` does with one: the reader's scan, the dataset built from its
// messages, every frame loaded again by location. A dataset or an Error(Format
// / Io) naming the file, never a crash, an out-of-bounds access, a leak (ASan)
// or undefined behaviour (UBSan); no allocation a length field chose beyond
// the reader's bound. The bytes live in a memory file (memfd), read through
// its /proc path like any file.
#include <sys/mman.h>
#include <unistd.h>

#include <string>

#include "fuzz_targets.hpp"
#include "sensor/dataset_mcap.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse::fuzz {

int mcap(const std::uint8_t* data, std::size_t size) {
    const int fd = ::memfd_create("fuzz.mcap", MFD_CLOEXEC);
    if (fd < 0) violated("memfd_create", "failed");
    for (std::size_t done = 0; done < size;) {
        const ssize_t n = ::write(fd, data + done, size - done);
        if (n <= 0) violated("memfd write", "failed");
        done += std::size_t(n);
    }
    const std::string path = "/proc/self/fd/" + std::to_string(fd);
    try {
        const Dataset d = sensor::read_mcap_dataset(path);
        for (const DatasetSensorRecord& s : d.sensors)
            for (const DatasetTake& t : s.takes)
                for (const DatasetFrame& f : t.frames) {
                    const Frame frame = load_frame(d, s, f);
                    if (frame.pixels.size() != std::size_t(s.info.width) * std::size_t(s.info.height) * 3)
                        violated(path.c_str(), "a loaded frame is not the sensor's size");
                }
    } catch (const Error& e) {
        const std::string what = e.what();
        if (e.kind() != ErrorKind::Format && e.kind() != ErrorKind::Io) violated("error kind", what.c_str());
        if (what.rfind(path + ": ", 0) != 0 || what.find('\n') != std::string::npos)
            violated("error message", what.c_str());
    }
    ::close(fd);
    return 0;
}

}  // namespace vkfuse::fuzz

VKFUSE_FUZZ_ENTRY(vkfuse::fuzz::mcap)

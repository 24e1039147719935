// record_dataset(): any sensor, every object under every setting, clean frames only.
#include "vkfuse/core/error.hpp"
#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/sensor/switching.hpp"

namespace vkfuse {

void record_dataset(Sensor& sensor, std::shared_ptr<Clock> clock, DatasetWriter& writer, const RecordOptions& options) {
    const SensorInfo info = sensor.info();
    if (options.grid.empty())
        throw Error(ErrorKind::InvalidArgument, info.serial + ": no illumination to record under");
    if (options.frames < 1 || options.background_frames < 1)
        throw Error(ErrorKind::InvalidArgument, info.serial + ": frames per setting must be >= 1");
    for (const Illumination& s : options.grid) s.check(info.leds);
    const std::size_t total = options.grid.size() * (std::size_t(options.background_frames) +
                                                     options.objects.size() * std::size_t(options.frames));
    std::size_t done = 0;
    auto place = [&](const std::string& object) {
        if (options.place_object) options.place_object(object);
    };
    // Calibrate with nothing pressed: the scene must stay still while the LEDs toggle.
    place("nothing");
    Switcher switcher(sensor, clock, measure_switch_timing(sensor, *clock));
    const int index = writer.add_sensor(info);
    auto take = [&](const std::string& object, bool background, int frames) {
        for (const Illumination& setting : options.grid) {
            for (const Frame& f : switcher.capture(setting, frames)) {
                writer.add_frame(index, object, background, f, setting);
                if (options.progress) options.progress(++done, total);
            }
        }
    };
    take("nothing", true, options.background_frames);
    for (const std::string& object : options.objects) {
        place(object);
        take(object, false, options.frames);
    }
}

}  // namespace vkfuse

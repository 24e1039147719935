// vkfuse.Dataset and vkfuse.Rig (compiled parts; python/vkfuse/_rig.py
// wraps them): recorded datasets read one frame at a time, and the rig of
// `vkfuse run`, opened from run's own options (tools/run/run_session.hpp) so
// that both take the same sensors - real DIGITs by serial, simulated ones, a
// replayed dataset, a capture host on ROS 2's wire - with the same checks:
//
//   ds = _vkfuse.Dataset("grid"); ds.take_length("SIM-0001", "coin"); ds.frame("SIM-0001", "coin", 0)
//   rig = _vkfuse.Rig(["--sensors", "2", "--virtual-clock"]); rig.next(); rig.close()
#include "rig.hpp"

#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>

#include "arrays.hpp"
#include "commands.hpp"
#include "run/run_session.hpp"
#include "sensors.hpp"
#include "shared.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/rig/rig.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::python {
namespace {

py::tuple levels_of(const Illumination& s) {
    py::tuple t(s.levels().size());
    for (std::size_t i = 0; i < s.levels().size(); ++i) t[i] = s.levels()[i];
    return t;
}

class PyDataset {
public:
    explicit PyDataset(const std::string& directory)
        : dataset_(std::make_shared<const Dataset>(read_dataset(directory))) {}

    std::string source() const { return dataset_->source; }
    std::string incomplete() const { return dataset_->incomplete; }
    std::vector<std::string> serials() const {
        std::vector<std::string> out;
        for (const auto& s : dataset_->sensors) out.push_back(s.info.serial);
        return out;
    }
    std::vector<std::string> objects() const { return dataset_->objects(); }

    // The frames of one sensor's take of `object` ("background" for the
    // background takes), in recording order: how many, and the i-th, loaded
    // when asked for (python/vkfuse/_rig.py walks them one by one).
    std::size_t take_length(const std::string& serial, const std::string& object) const {
        return take_frames(serial, object).size();
    }

    py::dict frame(const std::string& serial, const std::string& object, std::size_t i) const {
        const std::vector<const DatasetFrame*>& frames = take_frames(serial, object);
        if (i >= frames.size())
            throw Error(ErrorKind::InvalidArgument, "index " + std::to_string(i) + ": the take has " +
                                                        std::to_string(frames.size()) + " frames");
        const DatasetFrame& f = *frames[i];
        Frame frame;
        {
            py::gil_scoped_release unlocked;
            frame = load_frame(*dataset_, dataset_->sensor(serial), f);
        }
        py::dict d;
        d["pixels"] = pixels_of(frame);
        d["illumination"] = levels_of(f.illumination);
        d["index"] = f.index;
        d["timestamp"] = f.timestamp;
        d["cycle"] = f.cycle;
        d["file"] = f.file;
        return d;
    }

private:
    // Built once per take: a walk over a take's frames asks for each in turn.
    const std::vector<const DatasetFrame*>& take_frames(const std::string& serial, const std::string& object) const {
        const auto key = std::make_pair(serial, object);
        if (const auto it = takes_.find(key); it != takes_.end()) return it->second;
        const DatasetSensorRecord& record = dataset_->sensor(serial);
        std::vector<const DatasetFrame*> out;
        bool found = false;
        for (const DatasetTake& take : record.takes) {
            if (take.background ? object != "background" : take.object != object) continue;
            found = true;
            for (const DatasetFrame& f : take.frames) out.push_back(&f);
        }
        if (!found)
            throw Error(ErrorKind::InvalidArgument, dataset_->directory + ": sensor " + serial + " has no take of " + object);
        return takes_.emplace(key, std::move(out)).first->second;
    }

    std::shared_ptr<const Dataset> dataset_;  // never changes: the pointers below stay valid
    // (serial, object) -> its frames; touched only with the GIL held.
    mutable std::map<std::pair<std::string, std::string>, std::vector<const DatasetFrame*>> takes_;
};

class PyRig {
public:
    // argv: `vkfuse run`'s options (python/vkfuse/_rig.py spells them from
    // keyword arguments); those that write or publish are the wrapper's to refuse.
    explicit PyRig(const std::vector<std::string>& argv) {
        const cli::Args args = cli::Args::parse(cli::run_command.spec, argv);
        session_.options = cli::parse_run_options(args);
        cli::open_sources(session_, args);
        const cli::RunOptions& o = session_.options;
        Context* context = o.capture_only ? nullptr : open_backend(o.backend);
        backend_ = o.capture_only ? "none" : context ? "vulkan" : "cpu";
        RigConfig config = cli::rig_config(session_);
        config.want_fused = !o.capture_only;
        if (!context) config.cycles_in_flight = 1;  // the CPU path fuses each cycle as it is taken
        left_ = cli::cycle_target(session_);
        rig_ = std::make_unique<Rig>(context, std::move(config), session_.sensors.rig);
        py::gil_scoped_release unlocked;
        rig_->start();
    }

    // Cycles still to come: None for a live rig, else what --cycles or the
    // replayed recording leaves; 0 also once every sensor has failed.
    std::optional<int> cycles_left() const {
        if (!rig_ || rig_->all_failed()) return 0;
        return left_;
    }

    // Stops the sensors' capture threads and releases the sensors (idempotent).
    void close() {
        py::gil_scoped_release unlocked;
        rig_.reset();
    }

    // The next cycle: {"cycle", "capture_wait_s", "fuse_s", "sensors": [per sensor
    // {"serial", "status", "error", "metrics", "fused", "frames", "idle", "window_span_s"}]}.
    py::dict next() {
        if (!rig_) throw Error(ErrorKind::InvalidArgument, "rig: closed");
        CycleResult c;
        {
            py::gil_scoped_release unlocked;
            c = rig_->next();
        }
        if (session_.dataset) cli::report_as_recorded(c, *session_.dataset);
        if (left_) --*left_;
        py::dict d;
        d["cycle"] = c.cycle;
        d["capture_wait_s"] = c.capture_wait_s;
        d["fuse_s"] = c.fuse_s;
        py::list sensors;
        for (const SensorCycle& s : c.sensors) {
            py::dict e;
            e["serial"] = s.serial;
            e["status"] = std::string(to_string(s.status));
            e["error"] = s.error;
            const bool ok = s.status == SensorStatus::Ok;
            e["metrics"] = ok ? py::object(to_dict(s.metrics, MetricSet::all())) : py::none();
            e["fused"] = ok && s.fused ? py::object(to_array(*s.fused, false)) : py::none();
            py::list frames;
            for (const Frame& f : s.frames) frames.append(pixels_of(f));
            e["frames"] = frames;
            e["idle"] = s.skip.idle;
            e["window_span_s"] = ok ? py::object(py::float_(s.window_span_s())) : py::none();
            sensors.append(e);
        }
        d["sensors"] = sensors;
        return d;
    }

    std::vector<std::string> serials() const {
        std::vector<std::string> out;
        for (const RigSensor& r : session_.sensors.rig) out.push_back(r.sensor->info().serial);
        return out;
    }
    const std::string& backend() const { return backend_; }

    std::string object() const { return session_.options.object; }
    std::vector<std::vector<int>> sequence() const {
        std::vector<std::vector<int>> out;
        for (const Illumination& s : session_.options.sequence) out.emplace_back(s.levels().begin(), s.levels().end());
        return out;
    }

private:
    cli::RigSession session_;  // before rig_: its capture threads use the sensors
    std::unique_ptr<Rig> rig_;
    std::optional<int> left_;
    std::string backend_;
};

}  // namespace

void def_rig(py::module_& m) {
    py::class_<PyDataset>(m, "Dataset", "A recorded dataset (vkfuse sim, vkfuse run --record; a folder or an MCAP file): its sensors, objects and frames.")
        .def(py::init<const std::string&>(), py::arg("directory"))
        .def_property_readonly("source", &PyDataset::source)
        .def_property_readonly("incomplete", &PyDataset::incomplete,
                               "A recording cut short: where reading stopped and why; empty when whole.")
        .def_property_readonly("sensors", &PyDataset::serials, "The recorded sensors' serials.")
        .def("objects", &PyDataset::objects, "Objects with frames, in recording order (backgrounds excluded).")
        .def("take_length", &PyDataset::take_length, py::arg("serial"), py::arg("object"))
        .def("frame", &PyDataset::frame, py::arg("serial"), py::arg("object"), py::arg("index"),
             "One frame of a take: {pixels (H, W, 3) uint8, illumination (r, g, b), index, timestamp, cycle, file}.");
    py::class_<PyRig>(m, "Rig", "The rig of `vkfuse run`, opened from run's options (python/vkfuse/_rig.py).")
        .def(py::init<const std::vector<std::string>&>(), py::arg("argv"))
        .def("next", &PyRig::next, "The next cycle as a dict (cycle, capture_wait_s, fuse_s, sensors).")
        .def("cycles_left", &PyRig::cycles_left)
        .def("close", &PyRig::close)
        .def_property_readonly("sensors", &PyRig::serials)
        .def_property_readonly("backend", &PyRig::backend)
        .def_property_readonly("object", &PyRig::object)
        .def_property_readonly("sequence", &PyRig::sequence);
    // run's options as (name, value, help), for the wrapper's keyword
    // arguments and their help: one table for the CLI and Python.
    py::list options;
    for (const cli::OptionSpec& o : cli::run_command.spec.options)
        options.append(py::make_tuple(std::string(o.name), std::string(o.value), cli::option_help(o)));
    m.attr("run_options") = options;
}

}  // namespace vkfuse::python

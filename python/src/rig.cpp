// vkfuse.Dataset and vkfuse.Rig: recorded datasets and the multi-sensor rig
// from Python, every frame a numpy array and every cycle a dict:
//
//   ds = vkfuse.Dataset("grid")                        # vkfuse sim / vkfuse run --record
//   for f in ds.frames("SIM-0001", "coin"): f["pixels"], f["illumination"]
//   rig = vkfuse.Rig(sensors=2, sequence=[(15, 15, 15), (0, 15, 0)])   # simulated DIGITs
//   rig = vkfuse.Rig(dataset="run1")                   # or a recorded run played back
//   for cycle in rig.cycles(10): cycle["sensors"][0]["fused"], cycle["sensors"][0]["metrics"]
#include "rig.hpp"

#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "arrays.hpp"
#include "shared.hpp"
#include "vkfuse/core/error.hpp"
#include "vkfuse/rig/rig.hpp"
#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/sensor/sim_digit.hpp"

namespace vkfuse::python {
namespace {

py::array_t<std::uint8_t> pixels_of(const Frame& f) {
    py::array_t<std::uint8_t> out({py::ssize_t(f.height), py::ssize_t(f.width), py::ssize_t(3)});
    std::copy(f.pixels.begin(), f.pixels.end(), out.mutable_data());
    return out;
}

py::tuple levels_of(const Illumination& s) {
    py::tuple t(s.levels().size());
    for (std::size_t i = 0; i < s.levels().size(); ++i) t[i] = s.levels()[i];
    return t;
}

IlluminationSequence sequence_of(const std::vector<std::vector<int>>& settings) {
    if (settings.size() > kMaxSequenceSettings)
        throw Error(ErrorKind::InvalidArgument, "sequence: " + std::to_string(settings.size()) +
                                                    " settings in one cycle; at most " +
                                                    std::to_string(kMaxSequenceSettings));
    IlluminationSequence out;
    for (const auto& s : settings) {
        if (s.size() != 3)
            throw Error(ErrorKind::InvalidArgument,
                        "sequence: a setting of " + std::to_string(s.size()) + " levels; a DIGIT has 3 (r, g, b)");
        out.push_back(Illumination(s));
        out.back().check(LedLayout::digit());
    }
    return out;
}

class PyDataset {
public:
    explicit PyDataset(const std::string& directory)
        : dataset_(std::make_shared<const Dataset>(read_dataset(directory))) {}

    std::string source() const { return dataset_->source; }
    std::vector<std::string> serials() const {
        std::vector<std::string> out;
        for (const auto& s : dataset_->sensors) out.push_back(s.info.serial);
        return out;
    }
    std::vector<std::string> objects() const { return dataset_->objects(); }

    // The frames of one sensor's take of `object` ("background" for the
    // background takes), loaded one by one as the list is walked.
    py::list frames(const std::string& serial, const std::string& object) const {
        const DatasetSensorRecord& record = dataset_->sensor(serial);
        py::list out;
        bool found = false;
        for (const DatasetTake& take : record.takes) {
            if (take.background ? object != "background" : take.object != object) continue;
            found = true;
            for (const DatasetFrame& f : take.frames) {
                Frame frame;
                {
                    py::gil_scoped_release unlocked;
                    frame = load_frame(*dataset_, record, f);
                }
                py::dict d;
                d["pixels"] = pixels_of(frame);
                d["illumination"] = levels_of(f.illumination);
                d["index"] = f.index;
                d["timestamp"] = f.timestamp;
                d["cycle"] = f.cycle;
                d["file"] = f.file;
                out.append(d);
            }
        }
        if (!found)
            throw Error(ErrorKind::InvalidArgument, dataset_->directory + ": sensor " + serial + " has no take of " + object);
        return out;
    }

    std::shared_ptr<const Dataset> dataset() const { return dataset_; }

private:
    std::shared_ptr<const Dataset> dataset_;
};

class PyRig {
public:
    PyRig(int sensors, const std::optional<std::vector<std::vector<int>>>& sequence, const std::string& object,
          const std::optional<std::string>& dataset, const std::string& method, const std::string& wavelet,
          const std::optional<int>& levels, int background_frames, const std::string& backend) {
        RigConfig config;
        config.fusion = spec_of(method, wavelet, levels, "periodization", "mean", "max-abs");
        config.background_frames = background_frames;
        std::vector<RigSensor> rig_sensors;
        if (dataset) {
            auto recorded = std::make_shared<const Dataset>(read_dataset(*dataset));
            config.judging = FrameJudging::Label;
            if (sequence) {
                config.sequence = sequence_of(*sequence);
            } else if (recorded->run) {
                config.sequence = recorded->run->sequence;
            } else {
                throw Error(ErrorKind::InvalidArgument, "sequence: none given, and " + *dataset +
                                                            " was not recorded by vkfuse run (no sequence in it)");
            }
            // The recorded backgrounds come first in every setting's frames:
            // the replay takes them as its background, as `vkfuse run --replay` does.
            config.background_frames = recorded->background_frames(config.sequence);
            for (const DatasetSensorRecord& r : recorded->sensors)
                rig_sensors.push_back({std::make_shared<DatasetSensor>(recorded, r.info.serial, object), nullptr});
        } else {
            if (sensors < 1 || std::size_t(sensors) > kMaxRigSensors)
                throw Error(ErrorKind::InvalidArgument, "sensors " + std::to_string(sensors) + ": must be from 1 to " +
                                                            std::to_string(kMaxRigSensors));
            config.sequence = sequence_of(sequence.value_or(std::vector<std::vector<int>>{{15, 15, 15}, {0, 15, 0}}));
            for (int i = 0; i < sensors; ++i) {
                SimDigitOptions sim;
                sim.seed = std::uint64_t(i) + 1;
                sim.object = background_frames > 0 ? "nothing" : object;
                sim.serial = "SIM-" + std::string(4 - std::min<std::size_t>(4, std::to_string(i + 1).size()), '0') +
                             std::to_string(i + 1);
                // A virtual clock per sensor: deterministic, as fast as the host renders.
                sim.clock = make_virtual_clock();
                auto digit = std::make_shared<SimDigit>(sim);
                sims_.push_back(digit);
                rig_sensors.push_back({digit, sim.clock});
            }
            if (background_frames > 0)  // the object is pressed once the background is taken
                config.after_background = [this, object](std::size_t s) { sims_[s]->set_object(object, 1.0); };
        }
        if (config.sequence.empty()) throw Error(ErrorKind::InvalidArgument, "sequence: no setting given");
        Context* context = open_backend(backend);
        backend_ = context ? "vulkan" : "cpu";
        rig_ = std::make_unique<Rig>(context, std::move(config), std::move(rig_sensors));
        py::gil_scoped_release unlocked;
        rig_->start();
    }

    // The next cycle: {"cycle", "capture_wait_s", "fuse_s", "sensors": [per sensor
    // {"serial", "status", "error", "metrics", "fused", "frames", "idle"}]}.
    py::dict next() {
        CycleResult c;
        {
            py::gil_scoped_release unlocked;
            c = rig_->next();
        }
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
            sensors.append(e);
        }
        d["sensors"] = sensors;
        return d;
    }

    // The next `count` cycles, one by one. Ctrl-C (any Python signal
    // handler that raises) is seen between cycles: the cycles taken so far
    // are dropped with the exception, as a loop over next() would drop them.
    py::list cycles(int count) {
        if (count < 0) throw Error(ErrorKind::InvalidArgument, "cycles " + std::to_string(count) + ": must be >= 0");
        py::list out;
        for (int i = 0; i < count && !rig_->all_failed(); ++i) {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            out.append(next());
        }
        return out;
    }

    std::vector<std::string> serials() const {
        std::vector<std::string> out;
        for (std::size_t s = 0; s < rig_->sensors(); ++s) out.push_back(rig_->serial(s));
        return out;
    }
    const std::string& backend() const { return backend_; }

private:
    std::vector<std::shared_ptr<SimDigit>> sims_;  // before rig_: its threads use them
    std::unique_ptr<Rig> rig_;
    std::string backend_;
};

}  // namespace

void def_rig(py::module_& m) {
    py::class_<PyDataset>(m, "Dataset", "A recorded dataset (vkfuse sim, vkfuse run --record): its sensors, objects and frames.")
        .def(py::init<const std::string&>(), py::arg("directory"))
        .def_property_readonly("source", &PyDataset::source)
        .def_property_readonly("sensors", &PyDataset::serials, "The recorded sensors' serials.")
        .def("objects", &PyDataset::objects, "Objects with frames, in recording order (backgrounds excluded).")
        .def("frames", &PyDataset::frames, py::arg("serial"), py::arg("object"),
             "The frames of a take ('background' for the background takes): dicts of pixels (H, W, 3) uint8, "
             "illumination (r, g, b), index, timestamp, cycle, file.");
    py::class_<PyRig>(m, "Rig",
                      "Sensors cycling through an LED sequence, fused together every cycle: simulated DIGITs on "
                      "virtual clocks, or a recorded dataset played back (dataset=DIR).")
        .def(py::init<int, const std::optional<std::vector<std::vector<int>>>&, const std::string&,
                      const std::optional<std::string>&, const std::string&, const std::string&,
                      const std::optional<int>&, int, const std::string&>(),
             py::arg("sensors") = 1, py::arg("sequence") = py::none(), py::arg("object") = "coin",
             py::arg("dataset") = py::none(), py::arg("method") = "wavelet", py::arg("wavelet") = "bior4.4",
             py::arg("levels") = py::none(), py::arg("background_frames") = 0, py::arg("backend") = "auto")
        .def("next", &PyRig::next, "The next cycle as a dict (cycle, capture_wait_s, fuse_s, sensors).")
        .def("cycles", &PyRig::cycles, py::arg("count"), "The next count cycles (fewer once every sensor failed).")
        .def_property_readonly("sensors", &PyRig::serials)
        .def_property_readonly("backend", &PyRig::backend);
}

}  // namespace vkfuse::python

// A dataset's two forms, a folder and one MCAP recording, hold the same facts:
// written through DatasetWriter, read back through read_dataset and
// load_frame. Hostile recordings (not ours, lying messages, cut short) get
// one line naming the file and the record.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>

#include "dataset_frames.hpp"
#include "expect_error.hpp"
#include "io/mcap_writer.hpp"
#include "sensor/recording_messages.hpp"
#include "sensor/ros2_schema.hpp"
#include "temp_dir.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::test {
namespace {

const Illumination kWhite = Illumination::parse("15,15,15");
const Illumination kGreen = Illumination::parse("0,15,0");

// Two sensors, cycles interleaved as a rig records them: backgrounds, then
// per cycle each sensor's two frames; B misses cycle 2.
void write_rig(const std::string& path) {
    DatasetWriter w(path, "test rig");
    w.add_sensor(small_sensor("A-1"));
    w.add_sensor(small_sensor("B 2"));  // a space: its topic token is B_2
    FusionSpec fusion;
    fusion.method = Method::Laplacian;
    fusion.levels = 3;
    w.set_run({{kWhite, kGreen}, fusion, 1});
    std::uint64_t index[2] = {0, 0};
    for (int s = 0; s < 2; ++s)
        for (const Illumination& lit : {kWhite, kGreen}) w.add_frame(s, "nothing", true, pattern_frame(index[s]++, s), lit);
    for (int c = 0; c < 4; ++c)
        for (int s = 0; s < 2; ++s) {
            if (s == 1 && c == 2) {
                w.add_miss(1, {2, "timeout", "B 2: no frame within 5 s"});
                continue;
            }
            w.add_frame(s, "coin", false, pattern_frame(index[s]++, 10 * c + s), kWhite, c);
            w.add_frame(s, "coin", false, pattern_frame(index[s]++, 10 * c + s + 5), kGreen, c);
        }
    w.finish();
}

void expect_same_facts(const Dataset& a, const Dataset& b) {
    EXPECT_EQ(a.source, b.source);
    ASSERT_EQ(a.run.has_value(), b.run.has_value());
    if (a.run) {
        EXPECT_EQ(a.run->sequence, b.run->sequence);
        EXPECT_EQ(a.run->fusion.method, b.run->fusion.method);
        EXPECT_EQ(a.run->fusion.levels, b.run->fusion.levels);
        EXPECT_EQ(a.run->background_frames, b.run->background_frames);
    }
    ASSERT_EQ(a.sensors.size(), b.sensors.size());
    for (std::size_t i = 0; i < a.sensors.size(); ++i) {
        const DatasetSensorRecord &sa = a.sensors[i], &sb = b.sensors[i];
        EXPECT_EQ(sa.info.serial, sb.info.serial);
        EXPECT_EQ(sa.info.model, sb.info.model);
        EXPECT_EQ(sa.info.width, sb.info.width);
        EXPECT_EQ(sa.info.fps, sb.info.fps);
        EXPECT_EQ(sa.info.leds.names, sb.info.leds.names);
        ASSERT_EQ(sa.takes.size(), sb.takes.size());
        for (std::size_t t = 0; t < sa.takes.size(); ++t) {
            EXPECT_EQ(sa.takes[t].object, sb.takes[t].object);
            EXPECT_EQ(sa.takes[t].background, sb.takes[t].background);
            ASSERT_EQ(sa.takes[t].frames.size(), sb.takes[t].frames.size());
            for (std::size_t f = 0; f < sa.takes[t].frames.size(); ++f) {
                const DatasetFrame &fa = sa.takes[t].frames[f], &fb = sb.takes[t].frames[f];
                EXPECT_EQ(fa.index, fb.index);
                EXPECT_EQ(fa.timestamp, fb.timestamp);  // bit for bit
                EXPECT_EQ(fa.illumination, fb.illumination);
                EXPECT_EQ(fa.cycle, fb.cycle);
                const Frame pa = load_frame(a, sa, fa), pb = load_frame(b, sb, fb);
                EXPECT_EQ(pa.pixels, pb.pixels);
                EXPECT_EQ(pa.recorded_cycle, pb.recorded_cycle);
            }
        }
        ASSERT_EQ(sa.missed.size(), sb.missed.size());
        for (std::size_t m = 0; m < sa.missed.size(); ++m) {
            EXPECT_EQ(sa.missed[m].cycle, sb.missed[m].cycle);
            EXPECT_EQ(sa.missed[m].status, sb.missed[m].status);
            EXPECT_EQ(sa.missed[m].error, sb.missed[m].error);
        }
    }
}

TEST(DatasetMcap, HoldsWhatTheFolderHolds) {
    TempDir tmp;
    write_rig(tmp.file("rig"));
    write_rig(tmp.file("rig.mcap"));
    const Dataset folder = read_dataset(tmp.file("rig")), mcap = read_dataset(tmp.file("rig.mcap"));
    EXPECT_EQ(mcap.incomplete, "");
    ASSERT_EQ(mcap.sensors.size(), 2u);
    EXPECT_EQ(mcap.sensors[1].takes[1].frames.size(), 6u);
    EXPECT_EQ(mcap.sensors[1].missed.size(), 1u);
    expect_same_facts(folder, mcap);
    // Frames pixel for pixel as they were written.
    EXPECT_EQ(load_frame(mcap, mcap.sensors[0], mcap.sensors[0].takes[1].frames[3]).pixels, pattern_frame(5, 15).pixels);
}

TEST(DatasetMcap, AWriterRefusesSensorsAndRunsAfterTheFirstFrame) {
    TempDir tmp;
    const std::string path = tmp.file("late.mcap");
    DatasetWriter w(path, "test");
    w.add_sensor(small_sensor("A-1"));
    w.add_frame(0, "coin", false, pattern_frame(0, 0), kWhite);
    expect_error([&] { w.add_sensor(small_sensor("B-1")); }, path, ErrorKind::InvalidArgument, "after the first frame");
    expect_error([&] { w.set_run({{kWhite}, FusionSpec{}, 1}); }, path, ErrorKind::InvalidArgument,
                 "after the first frame");
    w.finish();
    expect_error([&] { DatasetWriter(path, "again"); }, path, ErrorKind::Io, "exists");
}

std::string bytes_of_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(DatasetMcap, ACutRecordingKeepsItsWholeCyclesOrSaysWhy) {
    TempDir tmp;
    write_rig(tmp.file("rig.mcap"));
    const std::string whole = bytes_of_file(tmp.file("rig.mcap"));
    for (std::size_t cut = 0; cut < whole.size(); cut += 37) {
        const std::string path = tmp.file("cut.mcap");
        std::ofstream(path, std::ios::binary | std::ios::trunc).write(whole.data(), std::streamsize(cut));
        try {
            const Dataset d = read_dataset(path);
            // Whole up to Data End: only the summary and footer are missing.
            if (!d.incomplete.empty()) {
                EXPECT_EQ(d.incomplete.rfind(path + ": byte ", 0), 0u) << d.incomplete;
            }
            // A cut recording keeps no cycle that one of its sensors did not finish.
            for (const DatasetSensorRecord& s : d.sensors)
                for (const DatasetTake& t : s.takes) {
                    std::map<std::int64_t, int> per_cycle;
                    for (const DatasetFrame& f : t.frames)
                        if (f.cycle >= 0) ++per_cycle[f.cycle];
                    for (const auto& [cycle, n] : per_cycle) EXPECT_EQ(n, 2) << cut << " cycle " << cycle;
                }
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Format) << e.what();
            EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
        }
    }
}

// An MCAP file written here record by record: what another program might hand us.
struct Forged {
    std::string path;
    std::FILE* file;
    io::mcap::Writer writer;
    explicit Forged(const std::string& p)
        : path(p), file(std::fopen(p.c_str(), "wb")), writer(file, p, {"ros2", "forger", 1 << 20, io::mcap::Compression::None}) {}
    void manifest(const std::string& json) { writer.add_metadata("vkfuse.dataset", {{"manifest", json}}); }
    std::uint16_t channel(const std::string& topic, const std::string& type, const std::string& schema_text) {
        const auto s = writer.add_schema(type, "ros2msg",
                                         {reinterpret_cast<const std::uint8_t*>(schema_text.data()), schema_text.size()});
        return writer.add_channel(s, topic, "cdr");
    }
    void message(std::uint16_t channel, const std::string& data) {
        writer.write(channel, 0, 0, 0, {reinterpret_cast<const std::uint8_t*>(data.data()), data.size()});
    }
    void close() {
        writer.finish();
        std::fclose(file);
    }
};

const char* kOneSensor =
    R"({"format": "vkfuse-dataset", "version": 1, "source": "forged", "sensors": [{"serial": "A-1", "model": "test",
        "width": 6, "height": 4, "fps": 60, "leds": {"model": "DIGIT", "channels": 3, "max_level": 15,
        "names": ["r", "g", "b"]}, "takes": []}]})";

TEST(DatasetMcap, RecordingsThatAreNotOursAreRefusedByName) {
    TempDir tmp;
    const std::string schema = sensor::ros2msg_schema("vkfuse_msgs/msg/RecordedFrame");
    const std::string good = sensor::recording::encode_frame("A-1", pattern_frame(0, 1), kWhite, "coin", false, 0);
    struct Case {
        std::string name;
        std::function<void(Forged&)> write;
        std::string fragment;
    };
    const Case cases[] = {
        {"no manifest", [&](Forged& f) { f.message(f.channel("/other", "x/msg/Y", "int32 a\n"), "x"); },
         "not a vkfuse recording"},
        {"another schema on our topic",
         [&](Forged& f) {
             f.manifest(kOneSensor);
             f.message(f.channel("/vkfuse/A_1/frame", "sensor_msgs/msg/Image", "uint32 height\n"), good);
         },
         "channel /vkfuse/A_1/frame: schema sensor_msgs/msg/Image (ros2msg) in cdr, not vkfuse's"},
        {"a frame of another serial",
         [&](Forged& f) {
             f.manifest(kOneSensor);
             f.message(f.channel("/vkfuse/A_1/frame", "vkfuse_msgs/msg/RecordedFrame", schema),
                       sensor::recording::encode_frame("Z-9", pattern_frame(0, 1), kWhite, "coin", false, 0));
         },
         "serial Z-9, not A-1"},
        {"a frame cut short",
         [&](Forged& f) {
             f.manifest(kOneSensor);
             f.message(f.channel("/vkfuse/A_1/frame", "vkfuse_msgs/msg/RecordedFrame", schema), good.substr(0, 40));
         },
         "not a RecordedFrame"},
        {"an object that is a path",
         [&](Forged& f) {
             f.manifest(kOneSensor);
             f.message(f.channel("/vkfuse/A_1/frame", "vkfuse_msgs/msg/RecordedFrame", schema),
                       sensor::recording::encode_frame("A-1", pattern_frame(0, 1), kWhite, "../../etc", false, 0));
         },
         "object:"},
        {"a level past the LEDs",
         [&](Forged& f) {
             f.manifest(kOneSensor);
             f.message(f.channel("/vkfuse/A_1/frame", "vkfuse_msgs/msg/RecordedFrame", schema),
                       sensor::recording::encode_frame("A-1", pattern_frame(0, 1), Illumination({16, 0, 0}), "coin", false, 0));
         },
         "level 16"},
        {"a manifest that lists frames",
         [&](Forged& f) {
             std::string m = kOneSensor;
             m.replace(m.find("\"takes\": []"), 11, R"("takes": [{"object": "coin", "background": false, "frames": []}])");
             f.manifest(m);
         },
         "lists frames"},
        {"two manifests", [&](Forged& f) { f.manifest(kOneSensor), f.manifest(kOneSensor); }, "two \"vkfuse.dataset\""},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string path = tmp.file(std::to_string(&c - cases) + ".mcap");
        Forged f(path);
        c.write(f);
        f.close();
        expect_error([&] { read_dataset(path); }, path, ErrorKind::Format, c.fragment);
    }
}

}  // namespace
}  // namespace vkfuse::test

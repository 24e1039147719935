// Datasets: PNG + manifest round trip, replay as a Sensor, malformed
// manifests, and recording from the simulated DIGIT.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "dataset_frames.hpp"
#include "expect_error.hpp"
#include "sensor_doubles.hpp"
#include "temp_dir.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::test {
namespace {

const Illumination kWhite = Illumination::parse("15,15,15");
const Illumination kGreen = Illumination::parse("0,15,0");

// Sensor A: 2 background frames per setting, then "coin" frames alternating settings.
std::string write_small_dataset(const TempDir& tmp) {
    const std::string dir = tmp.file("set");
    DatasetWriter w(dir, "test");
    const int a = w.add_sensor(small_sensor("A-1"));
    std::uint64_t index = 0;
    for (const Illumination& s : {kWhite, kGreen})
        for (int i = 0; i < 2; ++i) w.add_frame(a, "nothing", true, pattern_frame(index++, 0), s);
    for (int c = 0; c < 3; ++c) {
        w.add_frame(a, "coin", false, pattern_frame(index++, c), kWhite, c);
        w.add_frame(a, "coin", false, pattern_frame(index++, c + 10), kGreen, c);
    }
    w.set_run({{kWhite, kGreen}, FusionSpec{}, 2});
    w.finish();
    return dir;
}

TEST(Dataset, RoundTripsFramesAndManifest) {
    TempDir tmp;
    const Dataset d = read_dataset(write_small_dataset(tmp));
    EXPECT_EQ(d.source, "test");
    ASSERT_EQ(d.sensors.size(), 1u);
    const DatasetSensorRecord& s = d.sensor("A-1");
    EXPECT_EQ(s.info.width, 6);
    EXPECT_EQ(s.info.leds.names, LedLayout::digit().names);
    ASSERT_EQ(s.takes.size(), 2u);
    EXPECT_TRUE(s.takes[0].background);
    EXPECT_EQ(s.takes[1].object, "coin");
    ASSERT_EQ(s.takes[1].frames.size(), 6u);
    const DatasetFrame& f = s.takes[1].frames[3];
    EXPECT_EQ(f.index, 7u);
    EXPECT_EQ(f.timestamp, 0.1 + 7.0 / 60.0);  // bit for bit
    EXPECT_EQ(f.illumination, kGreen);
    EXPECT_EQ(f.cycle, 1);
    EXPECT_EQ(load_frame(d, s, f).pixels, pattern_frame(7, 11).pixels);
    ASSERT_TRUE(d.run);
    EXPECT_EQ(d.run->sequence, (IlluminationSequence{kWhite, kGreen}));
    EXPECT_EQ(d.run->background_frames, 2);
    EXPECT_EQ(d.objects(), std::vector<std::string>{"coin"});
}

TEST(DatasetSensor, PlaysEachSettingInRecordedOrderBackgroundsFirst) {
    TempDir tmp;
    auto d = std::make_shared<const Dataset>(read_dataset(write_small_dataset(tmp)));
    DatasetSensor sensor(d, "A-1", "coin");
    EXPECT_EQ(sensor.info().serial, "A-1");
    EXPECT_EQ(sensor.cycles_available({kWhite, kGreen}), 3u);
    EXPECT_EQ(sensor.cycles_available({kWhite, kWhite}), 1u);
    EXPECT_EQ(sensor.frames_lit_by(kGreen, true), 2u);
    sensor.set_illumination(kGreen);
    std::vector<std::uint64_t> green;
    for (int i = 0; i < 5; ++i) {
        const Frame f = sensor.grab();
        EXPECT_EQ(f.illumination, kGreen);
        green.push_back(f.index);
    }
    EXPECT_EQ(green, (std::vector<std::uint64_t>{2, 3, 5, 7, 9}));
    expect_error([&] { sensor.grab(); }, "A-1", ErrorKind::InvalidArgument,
                 "all 5 frames recorded under LEDs 0,15,0 played");
    sensor.set_illumination(kWhite);
    EXPECT_EQ(sensor.grab().index, 0u);
    expect_error([&] { sensor.set_illumination(Illumination::parse("1,2,3")); }, "A-1", ErrorKind::InvalidArgument,
                 "no frames recorded under LEDs 1,2,3");
}

TEST(DatasetSensor, UnknownSerialOrObjectIsNamed) {
    TempDir tmp;
    auto d = std::make_shared<const Dataset>(read_dataset(write_small_dataset(tmp)));
    expect_error([&] { DatasetSensor(d, "A-1", "lego"); }, "A-1", ErrorKind::InvalidArgument, "(has coin)");
    expect_error([&] { DatasetSensor(d, "B-9", "coin"); }, d->directory, ErrorKind::InvalidArgument, "no sensor B-9");
}

TEST(DatasetWriter, RefusesAnUsedDirectoryAndOddNames) {
    TempDir tmp;
    write_bytes(tmp.file("x"), "x");
    expect_error([&] { DatasetWriter(tmp.file(""), "test"); }, tmp.file(""), ErrorKind::Io, "not empty");
    DatasetWriter w(tmp.file("new"), "test");
    expect_error([&] { w.add_sensor(small_sensor("a/b")); }, "serial \"a/b\"", ErrorKind::InvalidArgument,
                 "file name");
    const int s = w.add_sensor(small_sensor("A"));
    expect_error([&] { w.add_frame(s, "..", false, pattern_frame(0, 0), kWhite); }, "object \"..\"",
                 ErrorKind::InvalidArgument, "file name");
}

// Each malformed manifest: a Format error naming the manifest, the place and the problem.
TEST(Dataset, MalformedManifestsSayWhereAndWhat) {
    TempDir tmp;
    const std::string dir = write_small_dataset(tmp);
    const std::string manifest = dir + "/manifest.json";
    const std::string good = read_bytes(manifest);
    auto with = [&](const std::string& from, const std::string& to) {
        std::string text = good;
        const std::size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        write_bytes(manifest, text.replace(at, from.size(), to));
    };
    struct Case {
        std::string from, to, fragment;
    };
    for (const Case& c : std::vector<Case>{
             {"\"format\"", "\"format\" x", "line 2: expected ':'"},
             {"\"width\": 6", "\"width\": -6", "sensors[0].width: expected an integer in 1..65536"},
             {"\"serial\": \"A-1\",", "", "sensors[0].serial: missing"},
             {"\"illumination\": \"0,15,0\"", "\"illumination\": \"0,16,0\"",
              "frames[2].illumination: illumination 0,16,0"},
             {"\"version\": 1", "\"version\": 7", "version: unsupported version"},
             {"\"method\": \"wavelet\"", "\"method\": \"fft\"", "run.method: --method: unknown method"}}) {
        SCOPED_TRACE(c.to);
        with(c.from, c.to);
        expect_error([&] { read_dataset(dir); }, manifest, ErrorKind::Format, c.fragment);
    }
    std::filesystem::remove(manifest);
    expect_error([&] { read_dataset(dir); }, manifest, ErrorKind::Io, "cannot open");
}

TEST(Dataset, RecordsCleanFramesFromTheSimulator) {
    TempDir tmp;
    SimDigitOptions o;
    o.clock = make_virtual_clock();
    o.object = "nothing";
    auto sim = std::make_shared<SimDigit>(o);
    TruthLoggingSensor sensor(sim);
    DatasetWriter writer(tmp.file("sim"), "test");
    RecordOptions rec;
    rec.objects = {"coin-heads", "lego"};
    rec.grid = {kWhite, kGreen, Illumination::parse("5,0,1")};
    rec.frames = 2;
    rec.background_frames = 3;
    std::vector<std::string> placed;
    rec.place_object = [&](const std::string& object) {
        placed.push_back(object);
        sim->set_object(object);
    };
    std::size_t last_done = 0, total = 0;
    rec.progress = [&](std::size_t done, std::size_t of) {
        last_done = done;
        total = of;
    };
    record_dataset(sensor, o.clock, writer, rec);
    writer.finish();
    EXPECT_EQ(placed, (std::vector<std::string>{"nothing", "coin-heads", "lego"}));
    EXPECT_EQ(total, 3u * (3 + 2 * 2));
    EXPECT_EQ(last_done, total);
    const Dataset d = read_dataset(tmp.file("sim"));
    const DatasetSensorRecord& s = d.sensor("SIM-0001");
    ASSERT_EQ(s.takes.size(), 3u);
    EXPECT_EQ(s.takes[0].frames.size(), 9u);
    for (const DatasetTake& t : s.takes)
        for (const DatasetFrame& f : t.frames) {
            const SimFrameTruth truth = sensor.truth(f.index);
            EXPECT_FALSE(truth.mixed) << f.file;
            EXPECT_EQ(truth.lit_by, f.illumination) << f.file;
        }
}

}  // namespace
}  // namespace vkfuse::test

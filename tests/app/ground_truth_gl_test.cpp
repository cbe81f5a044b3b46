// Ground truth for datasets through the binary (so GL): shapes, camera, masks and boxes agree
// with the trace and with each other, and are the same bytes for any --jobs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "discreel/encode.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::run_command;
using testing::TempDir;
using testing::write_file;

const std::string bin = DISCREEL_BIN;
const fs::path source_dir = DISCREEL_SOURCE_DIR;

// A CSV file as rows of named fields.
std::vector<std::map<std::string, std::string>> read_csv(const std::string& path) {
    std::istringstream lines(read_file(path));
    std::string line;
    std::getline(lines, line);
    std::vector<std::string> names;
    std::istringstream header(line);
    for (std::string name; std::getline(header, name, ',');) names.push_back(name);
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        std::map<std::string, std::string> row;
        std::size_t k = 0;
        for (std::string field; std::getline(fields, field, ',') && k < names.size(); ++k)
            row[names[k]] = field;
        rows.push_back(std::move(row));
    }
    return rows;
}

// Discs, boxes, a capsule and a hexagon falling onto a slope in a box: every body at least
// 4 pixels across at 128x128, none drawn over another's centre (they do not overlap).
constexpr const char* dataset_scene = R"(version: 1
video: {size: [128, 128], fps: 20, duration: 1.5}
walls:
  - box: [[0, 0], [4, 4]]
  - {segment: [[0, 1.5], [4, 0.5]], thickness: 0.06}
discs:
  - {id: a, position: [0.6, 3.2], radius: 0.2, velocity: [1, 0]}
  - {id: b, position: [1.4, 3.0], radius: 0.15}
  - {id: peg, position: [2.0, 2.0], radius: 0.2, static: true}
bodies:
  - {id: crate, box: [0.4, 0.3], position: [2.8, 3.2], angle: 0.3}
  - {id: rod, capsule: {length: 0.6, radius: 0.08}, position: [3.2, 2.4]}
  - {id: hex, polygon: [[0.22, 0], [0.11, 0.19], [-0.11, 0.19], [-0.22, 0], [-0.11, -0.19], [0.11, -0.19]], position: [1.0, 2.3]}
)";

class GroundTruthGLTest : public ::testing::Test {
protected:
    void SetUp() override { write_file(scene_, dataset_scene); }
    testing::CommandResult render(const std::string& out, std::vector<std::string> extra) {
        std::vector<std::string> argv{bin,         "render",   scene_,          "-o",
                                      dir_ / out,  "--trace",  dir_ / (out + ".trace.csv"),
                                      "--camera",  dir_ / (out + ".camera.csv"),
                                      "--masks",   dir_ / (out + ".masks"),
                                      "--boxes",   dir_ / (out + ".boxes.csv"),
                                      "--shapes",  dir_ / (out + ".shapes.json"), "-q"};
        argv.insert(argv.end(), extra.begin(), extra.end());
        return run_command(argv);
    }
    TempDir dir_;
    const std::string scene_ = dir_ / "set.yaml";
};

// Every body's trace position, through the camera file, lands on a pixel of its own mask id,
// inside its box; each box's pixel count is its mask's.
TEST_F(GroundTruthGLTest, MaskIdsMatchTheTraceThroughTheCamera) {
    const auto run = render("clip.mp4", {});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto trace = read_csv(dir_ / "clip.mp4.trace.csv");
    const auto camera = read_csv(dir_ / "clip.mp4.camera.csv");
    const auto boxes = read_csv(dir_ / "clip.mp4.boxes.csv");
    ASSERT_EQ(camera.size(), 30u);
    const std::vector<std::string> ids{"a", "b", "peg", "crate", "rod", "hex"};
    std::map<std::pair<int, std::string>, std::map<std::string, std::string>> box_of;
    for (const auto& row : boxes) box_of[{std::stoi(row.at("frame")), row.at("id")}] = row;
    int checked = 0;
    for (const auto& row : trace) {
        const int frame = std::stoi(row.at("frame"));
        const auto& m = camera.at(static_cast<std::size_t>(frame));
        ASSERT_EQ(std::stoi(m.at("frame")), frame);
        const double x = std::stod(row.at("x")), y = std::stod(row.at("y"));
        const double px = std::stod(m.at("m00")) * x + std::stod(m.at("m01")) * y +
                          std::stod(m.at("m02"));
        const double py = std::stod(m.at("m10")) * x + std::stod(m.at("m11")) * y +
                          std::stod(m.at("m12"));
        const int i = static_cast<int>(std::floor(px)), j = static_cast<int>(std::floor(py));
        if (i < 0 || j < 0 || i >= 128 || j >= 128) continue;
        char name[32];
        std::snprintf(name, sizeof name, "/mask_%05d.png", frame);
        const auto mask = encode::read_png_gray16(dir_ / "clip.mp4.masks" + name);
        ASSERT_TRUE(mask.ok()) << mask.error().message;
        ASSERT_EQ(mask->width, 128);
        const auto index = static_cast<std::size_t>(
            std::find(ids.begin(), ids.end(), row.at("id")) - ids.begin());
        ASSERT_LT(index, ids.size()) << row.at("id");
        EXPECT_EQ(mask->values[static_cast<std::size_t>(j) * 128 + static_cast<std::size_t>(i)],
                  index + 1)
            << row.at("id") << " at frame " << frame;
        const auto& box = box_of.at({frame, row.at("id")});
        EXPECT_LE(std::stoi(box.at("x0")), i);
        EXPECT_GE(std::stoi(box.at("x1")), i);
        EXPECT_LE(std::stoi(box.at("y0")), j);
        EXPECT_GE(std::stoi(box.at("y1")), j);
        const auto pixels = std::count(mask->values.begin(), mask->values.end(),
                                       static_cast<std::uint16_t>(index + 1));
        EXPECT_EQ(std::stol(box.at("pixels")), pixels);
        ++checked;
    }
    EXPECT_GE(checked, 150);   // six bodies, thirty frames, a few leaving the view at most
    // The walls are 65535, the background 0; nothing else but the six ids.
    const auto first = encode::read_png_gray16(dir_ / "clip.mp4.masks/mask_00000.png");
    ASSERT_TRUE(first.ok());
    EXPECT_EQ(first->values.front(), 0);   // the corner, outside the box of walls
    EXPECT_TRUE(std::all_of(first->values.begin(), first->values.end(), [](std::uint16_t v) {
        return v <= 6 || v == 65535;
    }));
    EXPECT_GT(std::count(first->values.begin(), first->values.end(), 65535), 200);
}

// The same bytes for every file, whatever --jobs; the shapes file says what each body is.
TEST_F(GroundTruthGLTest, TheSameBytesForAnyJobsAndShapesSayWhatEachBodyIs) {
    ASSERT_EQ(render("one.mp4", {"--jobs", "1"}).exit_code, 0);
    ASSERT_EQ(render("three.mp4", {"--jobs", "3"}).exit_code, 0);
    for (const char* side : {".camera.csv", ".boxes.csv", ".shapes.json"}) {
        EXPECT_EQ(read_file(dir_ / (std::string("one.mp4") + side)),
                  read_file(dir_ / (std::string("three.mp4") + side)))
            << side;
    }
    for (int frame = 0; frame < 30; ++frame) {
        char name[32];
        std::snprintf(name, sizeof name, "/mask_%05d.png", frame);
        EXPECT_EQ(read_file(dir_ / "one.mp4.masks" + name),
                  read_file(dir_ / "three.mp4.masks" + name))
            << frame;
    }
    const auto shapes = nlohmann::json::parse(read_file(dir_ / "one.mp4.shapes.json"));
    ASSERT_EQ(shapes["bodies"].size(), 6u);
    EXPECT_EQ(shapes["bodies"][0]["kind"], "circle");
    EXPECT_EQ(shapes["bodies"][0]["radius"], 0.2);
    EXPECT_EQ(shapes["bodies"][2]["static"], true);
    EXPECT_EQ(shapes["bodies"][2]["mass"], 0);
    EXPECT_EQ(shapes["bodies"][3]["kind"], "box");
    EXPECT_EQ(shapes["bodies"][3]["vertices"][2], (nlohmann::json{0.2, 0.15}));
    EXPECT_EQ(shapes["bodies"][4]["kind"], "capsule");
    EXPECT_EQ(shapes["bodies"][4]["length"], 0.6);
    EXPECT_EQ(shapes["bodies"][5]["kind"], "polygon");
    EXPECT_EQ(shapes["bodies"][5]["vertices"].size(), 6u);
    EXPECT_EQ(shapes["bodies"][5]["to"], 1.5);
    EXPECT_EQ(shapes["walls"].size(), 2u);
    EXPECT_EQ(shapes["walls"][0]["kind"], "box");
}

// A soundtrack has no frames to go with: ground truth beside a .wav is a bad command line,
// refused before any directory is made.
TEST_F(GroundTruthGLTest, ASoundtrackTakesNoGroundTruth) {
    const auto run = run_command({bin, "render", scene_, "-o", dir_ / "s.wav", "--masks",
                                  dir_ / "m"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: a .wav soundtrack has no frames: --trace, --events, --joints "
                       "and the ground truth come with a video or images\n");
    EXPECT_FALSE(fs::exists(dir_ / "m"));
}

// A respawning generator's sets are entries of their own, each with its time span.
TEST(GroundTruthShapesGLTest, EachRespawnedSetHasItsOwnEntries) {
    TempDir dir;
    const auto run = run_command({bin, "simulate", (source_dir / "configs/polygons.yaml").string(),
                                  "--duration", "9", "--shapes", dir / "s.json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto shapes = nlohmann::json::parse(read_file(dir / "s.json"));
    std::map<std::size_t, std::vector<std::pair<double, double>>> spans;
    for (const auto& body : shapes["bodies"]) {
        spans[body["index"].get<std::size_t>()].emplace_back(body["from"], body["to"]);
    }
    // respawn_every: 4 s over 9 s: the generated slots have three sets, 0-4, 4-8, 8-9.
    const auto three = std::count_if(spans.begin(), spans.end(), [](const auto& s) {
        return s.second ==
               std::vector<std::pair<double, double>>{{0.0, 4.0}, {4.0, 8.0}, {8.0, 9.0}};
    });
    EXPECT_GT(three, 0);
    for (const auto& [index, list] : spans) {
        EXPECT_EQ(list.front().first, 0.0) << index;
        EXPECT_EQ(list.back().second, 9.0) << index;
    }
}

}  // namespace
}  // namespace discreel

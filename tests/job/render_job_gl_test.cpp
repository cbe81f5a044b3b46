// The render-job layer's public API, as every front end uses it: values back, no printing,
// progress through a callback, cancellation that writes nothing, and the same bytes on one
// thread or three. "GL" in the suite names: render() needs an OSMesa context.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "discreel/job.hpp"
#include "test_support.hpp"

namespace discreel::job {
namespace {

namespace fs = std::filesystem;
using discreel::testing::read_file;
using discreel::testing::TempDir;

// 160x120, 24 fps, 1.25 s: 30 frames, with a flick at 0.5 s.
scene::Scene short_scene() {
    scene::LoadResult loaded =
        scene::load_scene_file(std::string(DISCREEL_SOURCE_DIR) + "/tests/data/scenes/short.yaml");
    EXPECT_TRUE(loaded.ok());
    return loaded.scene;
}

RenderDef mp4(const std::string& path) {
    RenderDef def;
    def.plan.scene = short_scene();
    def.plan.sink.path = path;
    def.plan.sink.preset = "ultrafast";
    return def;
}

TEST(RenderJobGLTest, RendersTheClipAndReportsProgressAsValues) {
    TempDir dir;
    RenderDef def = mp4(dir / "a.mp4");
    std::vector<int> done;
    def.on_progress = [&](const Progress& p) {
        EXPECT_EQ(p.frames_total, 30);
        done.push_back(p.frames_done);
    };
    const auto summary = render(def);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    EXPECT_EQ(summary->frames, 30);
    EXPECT_EQ(summary->range.first, 0);
    EXPECT_EQ(summary->range.last, 29);   // -1 resolved to the clip's last frame
    EXPECT_NE(summary->renderer.find("llvmpipe"), std::string::npos) << summary->renderer;
    ASSERT_EQ(done.size(), 30u);
    EXPECT_EQ(done.front(), 1);
    EXPECT_EQ(done.back(), 30);
    EXPECT_EQ(discreel::testing::probe_video(dir / "a.mp4")["nb_read_frames"], "30");

    RenderDef one_thread = mp4(dir / "b.mp4");
    one_thread.threaded = false;
    ASSERT_TRUE(render(one_thread).ok());
    EXPECT_EQ(read_file(dir / "a.mp4"), read_file(dir / "b.mp4"));
}

TEST(RenderJobGLTest, ARangeIsSimulatedFromTheStartAndDrawnFromItsFirstFrame) {
    TempDir dir;
    RenderDef def = mp4(dir / "frames_%02d.png");
    def.plan.sink.preset = "";   // an x264 setting, refused for PNG
    def.plan.frames = {.first = 28, .last = -1};
    const auto summary = render(def);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    EXPECT_EQ(summary->frames, 2);
    EXPECT_EQ(discreel::testing::directory_entries(dir.path()),
              (std::vector<std::string>{"frames_28.png", "frames_29.png"}));

    def.plan.frames = {.first = 10, .last = 30};
    const auto outside = render(def);
    ASSERT_FALSE(outside.ok());
    EXPECT_EQ(outside.error().message,
              "frames 10..30 are not in the clip, which has 30 frames");
}

TEST(RenderJobGLTest, CancelledJobsWriteNothing) {
    TempDir dir;
    RenderDef def = mp4(dir / "c.mp4");
    def.trace = dir / "c.csv";
    int polls = 0;
    def.should_stop = [&] { return ++polls > 5; };
    const auto summary = render(def);
    ASSERT_FALSE(summary.ok());
    EXPECT_EQ(summary.error().message, "cancelled; nothing was written");
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

// simulate() and render() see the same trajectory: their traces are the same bytes, and the
// summary's contact count is the events file's row count.
TEST(RenderJobGLTest, SimulateAgreesWithRender) {
    TempDir dir;
    RenderDef def = mp4(dir / "r.mp4");
    def.trace = dir / "r.csv";
    ASSERT_TRUE(render(def).ok());
    SimulateDef simulation;
    simulation.scene = short_scene();
    simulation.trace = dir / "s.csv";
    simulation.events = dir / "e.csv";
    const auto summary = simulate(simulation);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    EXPECT_EQ(read_file(dir / "s.csv"), read_file(dir / "r.csv"));
    EXPECT_EQ(summary->frames, 30);
    EXPECT_EQ(summary->steps, 580);   // frame 29 at 24 fps is t = 29/24 s = step 580 at 480 Hz
    const std::string events = read_file(dir / "e.csv");
    EXPECT_EQ(summary->contacts,
              static_cast<std::size_t>(std::count(events.begin(), events.end(), '\n') - 1));
    EXPECT_GT(summary->contacts, 0u);
}

}  // namespace
}  // namespace discreel::job

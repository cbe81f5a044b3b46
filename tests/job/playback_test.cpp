// Playback's checkpoints: a frame shown again after going back is the frame a playback from
// t = 0 shows, bit for bit (physics, trails, camera, what is drawn), for every shipped scene,
// and going back steps on from the nearest checkpoint, not from the start. "GL" in a suite's
// name: it draws through OSMesa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <vector>

#include "discreel/job.hpp"
#include "discreel/render.hpp"

namespace discreel::job {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> shipped_scenes() {
    std::vector<fs::path> scenes;
    for (const auto& entry : fs::directory_iterator(fs::path(DISCREEL_SOURCE_DIR) / "configs")) {
        if (entry.path().extension() == ".yaml") scenes.push_back(entry.path());
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

scene::Scene small(const fs::path& path) {
    scene::LoadResult loaded = scene::load_scene_file(path);
    EXPECT_TRUE(loaded.ok()) << path;
    loaded.scene.video.width = 160;
    loaded.scene.video.height = 90;
    return loaded.scene;
}

// What a frame is: every body's state (bits) and which body each pixel shows.
struct Seen {
    std::vector<physics::BodyState> bodies;
    std::vector<std::uint16_t> mask;
    render::Camera camera;
    std::size_t trails = 0;
};

Seen seen(Playback& playback, int frame, const scene::Scene& scene) {
    auto view = playback.show(frame, true);
    EXPECT_TRUE(view) << (view ? "" : view.error().message);
    if (!view) return {};
    const auto bodies = playback.bodies();
    return {{bodies.begin(), bodies.end()},
            render::draw_mask(**view, scene.video.width, scene.video.height),
            (*view)->camera,
            (*view)->trails.size()};
}

void expect_same(const Seen& a, const Seen& b) {
    ASSERT_EQ(a.bodies.size(), b.bodies.size());
    EXPECT_EQ(0, std::memcmp(a.bodies.data(), b.bodies.data(),
                             a.bodies.size() * sizeof(physics::BodyState)));
    EXPECT_TRUE(a.mask == b.mask);
    EXPECT_EQ(a.camera.center_x, b.camera.center_x);
    EXPECT_EQ(a.camera.center_y, b.camera.center_y);
    EXPECT_EQ(a.camera.height, b.camera.height);
    EXPECT_EQ(a.trails, b.trails);
}

TEST(PlaybackTest, AFrameShownAgainAfterGoingBackIsTheFrameFromTheStart) {
    for (const fs::path& path : shipped_scenes()) {
        SCOPED_TRACE(path.filename().string());
        const scene::Scene scene = small(path);
        const int last = scene.video.frame_count() - 1;
        const int later = std::min(last, 150), earlier = std::min(last, 47);
        Playback fresh(scene);
        const Seen expected = seen(fresh, earlier, scene);

        Playback scrubbed(scene, {.checkpoint_every = 20,
                                  .max_checkpoints = 1 << 20,
                                  .max_checkpoint_bytes = 0});
        (void)seen(scrubbed, later, scene);
        const Seen again = seen(scrubbed, earlier, scene);
        expect_same(expected, again);
        // And on from there, as the fresh one goes on.
        expect_same(seen(fresh, later, scene), seen(scrubbed, later, scene));
    }
}

TEST(PlaybackTest, GoingBackStepsOnFromTheNearestCheckpoint) {
    const scene::Scene scene = small(fs::path(DISCREEL_SOURCE_DIR) / "configs/pyramid.yaml");
    Playback playback(
        scene, {.checkpoint_every = 10, .max_checkpoints = 1 << 20, .max_checkpoint_bytes = 0});
    ASSERT_TRUE(playback.show(100, true));
    const std::int64_t once = playback.steps_taken();
    EXPECT_EQ(once, playback.world().step_count());
    EXPECT_EQ(10U, playback.checkpoints());   // frames 10, 20, ..., 100 (0: the scene's)
    // Frame 95: from the checkpoint at 90, five frames of steps, not ninety-five.
    ASSERT_TRUE(playback.show(95, true));
    const std::int64_t per_frame = scene.physics.rate / scene.video.fps;
    EXPECT_EQ(once + 5 * per_frame, playback.steps_taken());
    EXPECT_EQ(96, playback.next_frame());
    // The same frame twice: from its checkpoint, no steps at all.
    ASSERT_TRUE(playback.show(90, true));
    EXPECT_EQ(once + 5 * per_frame, playback.steps_taken());
    // Before the first checkpoint: from t = 0.
    ASSERT_TRUE(playback.show(3, true));
    EXPECT_EQ(once + 8 * per_frame, playback.steps_taken());
    // Far ahead again: from the checkpoint at 70, not from frame 4.
    ASSERT_TRUE(playback.show(72, true));
    EXPECT_EQ(once + 10 * per_frame, playback.steps_taken());
}

TEST(PlaybackTest, PastTheirBoundCheckpointsAreThinnedOut) {
    const scene::Scene scene = small(fs::path(DISCREEL_SOURCE_DIR) / "configs/demo.yaml");
    Playback playback(scene,
                      {.checkpoint_every = 10, .max_checkpoints = 4, .max_checkpoint_bytes = 0});
    Playback fresh(scene);
    ASSERT_TRUE(playback.show(100, true));
    // 10, 20, 30, 40, 50: one too many, so 20 and 40 stay; then 60, 80, 100: one too many
    // again, so 40 and 80 stay.
    EXPECT_EQ(2U, playback.checkpoints());
    const std::int64_t once = playback.steps_taken();
    const Seen back = seen(playback, 79, scene);   // from 40: 39 frames
    const std::int64_t per_frame = scene.physics.rate / scene.video.fps;
    EXPECT_EQ(once + 39 * per_frame, playback.steps_taken());
    expect_same(seen(fresh, 79, scene), back);
}

// A bound in bytes counts what a checkpoint copies: the world, and the trails' ring, which
// long trails make the larger part.
TEST(PlaybackTest, ABoundInBytesCountsTheTrails) {
    scene::Scene scene = small(fs::path(DISCREEL_SOURCE_DIR) / "configs/demo.yaml");
    const double plain = Playback(scene).checkpoint_bytes();
    scene.style.trails.enabled = true;
    scene.style.trails.length = 10;   // seconds: 601 rows of every moving body
    const double trailed = Playback(scene).checkpoint_bytes();
    std::size_t moving = 0;
    for (const scene::Body& b : scene.bodies) moving += b.is_static ? 0 : 1;
    const double ring = 601.0 * static_cast<double>(moving) * 3 * sizeof(float);
    EXPECT_GE(trailed - plain, ring);
    EXPECT_LT(trailed - plain, 1.01 * ring);

    Playback bounded(scene, {.checkpoint_every = 10,
                             .max_checkpoints = 1 << 20,
                             .max_checkpoint_bytes = 3.5 * trailed});
    ASSERT_TRUE(bounded.show(100, false));
    // Three fit: 10, 20, 30, 40 is one too many, so 20 and 40 stay; 60, then 80 is one too
    // many again, so 40 and 80 stay.
    EXPECT_EQ(2U, bounded.checkpoints());
}

TEST(PlaybackTest, WithoutCheckpointsFramesGoForwardOnly) {
    const scene::Scene scene = small(fs::path(DISCREEL_SOURCE_DIR) / "configs/demo.yaml");
    Playback playback(scene);
    ASSERT_TRUE(playback.show(10, true));
    const auto back = playback.show(5, true);
    ASSERT_FALSE(back);
    EXPECT_EQ("frame 5 comes before frame 11, shown already: frames go forward only",
              back.error().message);
    const auto outside = playback.show(scene.video.frame_count(), true);
    ASSERT_FALSE(outside);
    EXPECT_EQ("frame " + std::to_string(scene.video.frame_count()) +
                  " is not in the clip, which has " + std::to_string(scene.video.frame_count()) +
                  " frames",
              outside.error().message);
}

TEST(PlaybackTest, PlayHandsOverEveryFrameAndDrawsOnlyThoseAsked) {
    const scene::Scene scene = small(fs::path(DISCREEL_SOURCE_DIR) / "configs/demo.yaml");
    Playback playback(scene);
    std::vector<int> frames, drawn;
    ASSERT_TRUE(playback.play({.last = 12,
                               .drawn = [](int f) { return f % 5 == 0; },
                               .look = true,
                               .should_stop = {}, .until = {}},
                              [&](const ShownFrame& shown) -> Status {
                                  frames.push_back(shown.frame);
                                  if (shown.view != nullptr) drawn.push_back(shown.frame);
                                  EXPECT_DOUBLE_EQ(shown.frame / double(scene.video.fps), shown.t);
                                  return {};
                              }));
    EXPECT_EQ(13U, frames.size());
    EXPECT_EQ((std::vector<int>{0, 5, 10}), drawn);
    // An error of the caller's ends the play with it.
    const Status stopped = playback.play({}, [](const ShownFrame& shown) -> Status {
        if (shown.frame == 15) return Error{"enough"};
        return {};
    });
    ASSERT_FALSE(stopped);
    EXPECT_EQ("enough", stopped.error().message);
    EXPECT_EQ(16, playback.next_frame());
}

TEST(PlaybackGLTest, AFrameDrawnAfterGoingBackHasTheSameBytes) {
    for (const char* name : {"polygons.yaml", "bridge.yaml", "windmill.yaml"}) {
        SCOPED_TRACE(name);
        const scene::Scene scene = small(fs::path(DISCREEL_SOURCE_DIR) / "configs" / name);
        auto renderer = render::Renderer::create({.width = 160, .height = 90});
        ASSERT_TRUE(renderer) << renderer.error().message;
        Playback fresh(scene);
        auto view = fresh.show(60, true);
        ASSERT_TRUE(view);
        auto expected = renderer->draw(**view);
        ASSERT_TRUE(expected);
        const std::vector<std::uint8_t> bytes(expected->rgba.begin(), expected->rgba.end());
        Playback scrubbed(scene, {.checkpoint_every = 25,
                                  .max_checkpoints = 1 << 20,
                                  .max_checkpoint_bytes = 0});
        ASSERT_TRUE(scrubbed.show(140, true));
        view = scrubbed.show(60, true);
        ASSERT_TRUE(view);
        auto again = renderer->draw(**view);
        ASSERT_TRUE(again);
        EXPECT_TRUE(std::equal(bytes.begin(), bytes.end(), again->rgba.begin(), again->rgba.end()));
    }
}

}  // namespace
}  // namespace discreel::job

// What a scene gets for every key it leaves out.
#include <numbers>

#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using testing::load_ok;

TEST(Defaults, AMinimalSceneGetsTheDocumentedDefaults) {
    const Scene s = load_ok("version: 1\n");
    EXPECT_EQ(s.video.width, 1280);
    EXPECT_EQ(s.video.height, 720);
    EXPECT_EQ(s.video.fps, 60);
    EXPECT_EQ(s.video.duration, 8.0);
    EXPECT_EQ(s.video.background, (Color{0x0f, 0x14, 0x19, 0xff}));
    EXPECT_FALSE(s.camera.center.has_value());
    EXPECT_FALSE(s.camera.height.has_value());
    EXPECT_EQ(s.physics.gravity, (Vec2{0, -9.81}));
    EXPECT_EQ(s.physics.rate, 480);
    EXPECT_EQ(s.physics.substeps, 0);     // automatic: each at or under 1/480 s
    EXPECT_EQ(s.physics.iterations, 0);   // the solver's own
    EXPECT_TRUE(s.physics.sleep);
    EXPECT_EQ(s.physics.restitution, 0.8);
    EXPECT_EQ(s.physics.friction, 0.2);
    EXPECT_EQ(s.physics.seed, 1u);
    EXPECT_TRUE(s.walls.empty());
    EXPECT_TRUE(s.bodies.empty());
    EXPECT_TRUE(s.throws.empty());
    // 480 frames: first, middle (480 / 2) and last.
    EXPECT_EQ(s.golden_frames, (std::vector<int>{0, 240, 479}));
}

TEST(Defaults, DiscsTakeIndexIdsDensityMassAndPhysicsMaterials) {
    const Scene s = load_ok(R"(version: 1
physics:
  restitution: 0.5
  friction: 0.7
discs:
  - position: [0, 0]
    radius: 0.5
  - position: [2, 0]
    radius: 0.5
    density: 3
  - position: [4, 0]
    radius: 0.25
    static: true
)");
    ASSERT_EQ(s.bodies.size(), 3u);
    const Body& d = s.bodies[0];
    EXPECT_EQ(d.id, "0");
    EXPECT_EQ(d.velocity, (Vec2{0, 0}));
    EXPECT_EQ(d.angle, 0);
    EXPECT_EQ(d.angular_velocity, 0);
    EXPECT_DOUBLE_EQ(d.mass, std::numbers::pi * 0.25);  // density 1 kg/m^2 * pi r^2
    EXPECT_EQ(d.restitution, 0.5);
    EXPECT_EQ(d.friction, 0.7);
    EXPECT_FALSE(d.is_static);
    EXPECT_EQ(s.bodies[1].id, "1");
    EXPECT_DOUBLE_EQ(s.bodies[1].mass, 3 * std::numbers::pi * 0.25);
    // A static disc keeps a mass (physics ignores it).
    EXPECT_TRUE(s.bodies[2].is_static);
    EXPECT_DOUBLE_EQ(s.bodies[2].mass, std::numbers::pi * 0.0625);
}

TEST(Defaults, ColoursComeFromAPaletteByIndexThatCycles) {
    std::string yaml = "version: 1\ndiscs:\n";
    for (int i = 0; i < 9; ++i)
        yaml += "  - {position: [" + std::to_string(2 * i) + ", 0], radius: 0.5}\n";
    const Scene s = load_ok(yaml);
    ASSERT_EQ(s.bodies.size(), 9u);
    EXPECT_EQ(s.bodies[0].color, (Color{0xf4, 0xd3, 0x5e, 0xff}));
    EXPECT_EQ(s.bodies[1].color, (Color{0xe4, 0x57, 0x2e, 0xff}));
    for (int i = 1; i < 8; ++i) EXPECT_NE(s.bodies[i].color, s.bodies[0].color) << i;
    EXPECT_EQ(s.bodies[8].color, s.bodies[0].color);  // eight colours, then round again
}

TEST(Defaults, WallsTakeThePhysicsMaterialsAndAThinGreyLine) {
    const Scene s = load_ok(R"(version: 1
physics: {restitution: 0.3, friction: 0.4}
walls:
  - box: [[4, 3], [0, 0]]
)");
    ASSERT_EQ(s.walls.size(), 1u);
    EXPECT_EQ(s.walls[0].a, (Vec2{0, 0}));  // corners in any order: min and max
    EXPECT_EQ(s.walls[0].b, (Vec2{4, 3}));
    EXPECT_EQ(s.walls[0].thickness, 0.02);
    EXPECT_EQ(s.walls[0].restitution, 0.3);
    EXPECT_EQ(s.walls[0].friction, 0.4);
    EXPECT_EQ(s.walls[0].color, (Color{0x88, 0x99, 0xaa, 0xff}));
}

TEST(Defaults, GoldenFramesAreFirstMiddleLastWithoutRepeats) {
    EXPECT_EQ(load_ok("version: 1\nvideo: {fps: 30, duration: 2}\n").golden_frames,
              (std::vector<int>{0, 30, 59}));
    EXPECT_EQ(load_ok("version: 1\nvideo: {fps: 1, duration: 1}\n").golden_frames,
              (std::vector<int>{0}));
    EXPECT_EQ(load_ok("version: 1\nvideo: {fps: 1, duration: 2}\n").golden_frames,
              (std::vector<int>{0, 1}));
}

TEST(Defaults, FrameCountRoundsDurationTimesFps) {
    EXPECT_EQ(load_ok("version: 1\nvideo: {fps: 30, duration: 0.05}\n").video.frame_count(), 2);
    EXPECT_EQ(load_ok("version: 1\nvideo: {fps: 24, duration: 1.02}\n").video.frame_count(), 24);
}

// discreel's own keys: the solver's substeps and iterations, for tuning a heavy scene.
TEST(Defaults, PhysicsSubstepsAndIterationsAreRead) {
    const Scene s = load_ok("version: 1\nphysics: {rate: 400, substeps: 1, iterations: 5}\n");
    EXPECT_EQ(s.physics.rate, 400);
    EXPECT_EQ(s.physics.substeps, 1);
    EXPECT_EQ(s.physics.iterations, 5);
    EXPECT_FALSE(load_ok("version: 1\nphysics: {sleep: false}\n").physics.sleep);
}

TEST(Defaults, EmptySectionsAreAllowed) {
    const Scene s = load_ok("version: 1\nvideo:\nphysics:\nwalls:\ndiscs:\nthrows:\n");
    EXPECT_EQ(s.video.fps, 60);
    EXPECT_TRUE(s.bodies.empty());
}

TEST(Defaults, ThrowsNameDiscsByIdByIndexOrByQuotedId) {
    const Scene s = load_ok(R"(version: 1
discs:
  - {id: "1", position: [0, 0], radius: 0.5}
  - {id: b, position: [2, 0], radius: 0.5}
throws:
  - {disc: 1, velocity: [1, 0]}
  - {disc: "1", velocity: [1, 0]}
  - {disc: b, velocity: [1, 0]}
)");
    ASSERT_EQ(s.throws.size(), 3u);
    EXPECT_EQ(s.throws[0].body, 1u);  // a plain number is an index
    EXPECT_EQ(s.throws[1].body, 0u);  // quoted, it is an id
    EXPECT_EQ(s.throws[2].body, 1u);
    EXPECT_EQ(s.throws[0].at, 0.0);   // a flick without `at` happens at the start
}

}  // namespace
}  // namespace discreel::scene

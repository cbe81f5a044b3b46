// The contract's example scene, with every key: each value must arrive resolved in Scene.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using testing::load_ok;

constexpr std::string_view every_key = R"(version: 1
video:
  size: [1280, 720]
  fps: 60
  duration: 8.0
  background: "#0f1419"
camera:
  center: [6.4, 3.6]
  height: 7.2
physics:
  gravity: [0, -9.81]
  rate: 480
  restitution: 0.8
  friction: 0.2
  seed: 1
walls:
  - box: [[0, 0], [12.8, 7.2]]
  - segment: [[2, 1], [5, 2]]
    thickness: 0.05
    restitution: 1.0
    friction: 0.5
    color: "#8899aa"
discs:
  - id: cue
    position: [2, 3.6]
    velocity: [0.5, -1]
    angle: 0.25
    angular_velocity: 3
    radius: 0.3
    mass: 1.5
    restitution: 0.9
    friction: 0.1
    color: "#f4d35e80"
    static: false
  - grid:
      origin: [4, 1]
      count: [10, 6]
      spacing: [0.5, 0.5]
      radius: 0.2
      jitter: 0.02
      colors: ["#e4572e", "#76b041", "#17bebb"]
  - random:
      count: 200
      region: [[1, 1], [11, 6]]
      radius: [0.1, 0.25]
      speed: [0, 2]
throws:
  - disc: cue
    at: 1.0
    velocity: [12, 3]
  - disc: 3
    path:
      - [1.0, 3.0, 3.0]
      - [1.3, 4.0, 4.0]
      - [1.5, 6.0, 4.5]
    release: [10, 2]
golden:
  frames: [0, 60, 119]
)";

TEST(FullScene, VideoCameraAndPhysicsKeepTheirValues) {
    const Scene s = load_ok(every_key);
    EXPECT_EQ(s.name, "s");
    EXPECT_EQ(s.version, 1);
    EXPECT_EQ(s.video.width, 1280);
    EXPECT_EQ(s.video.height, 720);
    EXPECT_EQ(s.video.fps, 60);
    EXPECT_EQ(s.video.duration, 8.0);
    EXPECT_EQ(s.video.frame_count(), 480);
    EXPECT_EQ(s.video.background, (Color{0x0f, 0x14, 0x19, 0xff}));
    EXPECT_EQ(s.camera.center, (Vec2{6.4, 3.6}));
    EXPECT_EQ(s.camera.height, 7.2);
    EXPECT_EQ(s.physics.gravity, (Vec2{0, -9.81}));
    EXPECT_EQ(s.physics.rate, 480);
    EXPECT_EQ(s.physics.restitution, 0.8);
    EXPECT_EQ(s.physics.friction, 0.2);
    EXPECT_EQ(s.physics.seed, 1u);
    EXPECT_EQ(s.golden_frames, (std::vector<int>{0, 60, 119}));
}

TEST(FullScene, WallsTakeOverridesOrThePhysicsDefaults) {
    const Scene s = load_ok(every_key);
    ASSERT_EQ(s.walls.size(), 2u);
    const Wall& box = s.walls[0];
    EXPECT_EQ(box.shape, Wall::Shape::box);
    EXPECT_EQ(box.a, (Vec2{0, 0}));
    EXPECT_EQ(box.b, (Vec2{12.8, 7.2}));
    EXPECT_EQ(box.thickness, 0.02);
    EXPECT_EQ(box.restitution, 0.8);
    EXPECT_EQ(box.friction, 0.2);
    const Wall& segment = s.walls[1];
    EXPECT_EQ(segment.shape, Wall::Shape::segment);
    EXPECT_EQ(segment.a, (Vec2{2, 1}));
    EXPECT_EQ(segment.b, (Vec2{5, 2}));
    EXPECT_EQ(segment.thickness, 0.05);
    EXPECT_EQ(segment.restitution, 1.0);
    EXPECT_EQ(segment.friction, 0.5);
    EXPECT_EQ(segment.color, (Color{0x88, 0x99, 0xaa, 0xff}));
}

TEST(FullScene, EveryDiscKeyArrives) {
    const Scene s = load_ok(every_key);
    ASSERT_EQ(s.bodies.size(), 1u + 60u + 200u);
    const Body& cue = s.bodies[0];
    EXPECT_EQ(cue.id, "cue");
    EXPECT_EQ(cue.position, (Vec2{2, 3.6}));
    EXPECT_EQ(cue.velocity, (Vec2{0.5, -1}));
    EXPECT_EQ(cue.angle, 0.25);
    EXPECT_EQ(cue.angular_velocity, 3);
    EXPECT_EQ(cue.radius, 0.3);
    EXPECT_EQ(cue.mass, 1.5);
    EXPECT_EQ(cue.restitution, 0.9);
    EXPECT_EQ(cue.friction, 0.1);
    EXPECT_EQ(cue.color, (Color{0xf4, 0xd3, 0x5e, 0x80}));
    EXPECT_FALSE(cue.is_static);
}

TEST(FullScene, GeneratorsExpandInPlaceWithTheirIds) {
    const Scene s = load_ok(every_key);
    EXPECT_EQ(s.bodies[1].id, "1.0");
    EXPECT_EQ(s.bodies[60].id, "1.59");
    EXPECT_EQ(s.bodies[61].id, "2.0");
    EXPECT_EQ(s.bodies[260].id, "2.199");
    // Grid colours cycle in disc order.
    EXPECT_EQ(s.bodies[1].color, (Color{0xe4, 0x57, 0x2e, 0xff}));
    EXPECT_EQ(s.bodies[2].color, (Color{0x76, 0xb0, 0x41, 0xff}));
    EXPECT_EQ(s.bodies[3].color, (Color{0x17, 0xbe, 0xbb, 0xff}));
    EXPECT_EQ(s.bodies[4].color, (Color{0xe4, 0x57, 0x2e, 0xff}));
    // Grid disc 11 is column 1 of row 1, within the jitter of its lattice point.
    EXPECT_NEAR(s.bodies[1 + 11].position.x, 4.5, 0.02);
    EXPECT_NEAR(s.bodies[1 + 11].position.y, 1.5, 0.02);
    EXPECT_EQ(s.bodies[1 + 11].radius, 0.2);
    EXPECT_DOUBLE_EQ(s.bodies[1 + 11].mass, std::numbers::pi * 0.2 * 0.2);
}

TEST(FullScene, ThrowsResolveToDiscIndices) {
    const Scene s = load_ok(every_key);
    ASSERT_EQ(s.throws.size(), 2u);
    const Throw& flick = s.throws[0];
    EXPECT_EQ(flick.body, 0u);
    EXPECT_EQ(flick.at, 1.0);
    EXPECT_EQ(flick.velocity, (Vec2{12, 3}));
    EXPECT_TRUE(flick.path.empty());
    EXPECT_FALSE(flick.release.has_value());
    const Throw& grab = s.throws[1];
    EXPECT_EQ(grab.body, 3u);
    EXPECT_FALSE(grab.velocity.has_value());
    ASSERT_EQ(grab.path.size(), 3u);
    EXPECT_EQ(grab.path[1].t, 1.3);
    EXPECT_EQ(grab.path[1].position, (Vec2{4.0, 4.0}));
    EXPECT_EQ(grab.at, 1.0);  // a grab starts at its first waypoint
    EXPECT_EQ(grab.release, (Vec2{10, 2}));
}

TEST(FullScene, LoadingFromAFileNamesTheSceneAfterIt) {
    const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "cradle.yaml";
    {
        std::ofstream out(path);
        out << every_key;
    }
    const LoadResult result = load_scene_file(path);
    EXPECT_TRUE(result.ok());
    EXPECT_EQ(result.scene.name, "cradle");
    EXPECT_EQ(result.scene.bodies.size(), 261u);
    std::filesystem::remove(path);
}

TEST(FullScene, AMissingFileIsOneProblemAboutTheFile) {
    const LoadResult result = load_scene_file("no/such/scene.yaml");
    ASSERT_EQ(result.diagnostics.size(), 1u);
    EXPECT_EQ(result.diagnostics[0].to_string(), "no/such/scene.yaml: no such file");
}

}  // namespace
}  // namespace discreel::scene

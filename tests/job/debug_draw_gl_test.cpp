// style.debug: what the physics reports of contacts and sleep (World::contact_points and
// sleeping, against the weights at rest), what the frame draws of it, and a golden of all six
// drawings over a small scene. "GL" in a suite's name: it draws through OSMesa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "../render/golden_check.hpp"
#include "discreel/job.hpp"
#include "discreel/render.hpp"

namespace discreel::job {
namespace {

// A ball and a crate with a lid resting on the floor (asleep by 1.5 s), and a bob hanging on
// a rod; every debug drawing on.
constexpr std::string_view at_rest = R"(version: 1
video: {size: [320, 180], fps: 30, duration: 2, background: "#0f1419"}
camera: {center: [1.6, 0.8], height: 1.8}
physics: {gravity: [0, -9.81], restitution: 0.2}
style: {spin_marker: false, debug: [contacts, normals, impulses, boxes, joints, sleep]}
walls:
  - box: [[0, 0], [3.2, 1.8]]
discs:
  - {id: ball, position: [0.6, 0.25], radius: 0.25, color: "#f4d35e"}
  - {id: bob, position: [2.6, 0.9], radius: 0.12, color: "#17bebb"}
bodies:
  - {id: crate, box: [0.6, 0.4], position: [1.5, 0.2], color: "#e4572e"}
  - {id: lid, box: [0.3, 0.2], position: [1.5, 0.5], color: "#76b041"}
joints:
  - distance: {b: bob, anchor_a: [2.6, 1.6], anchor_b: [2.6, 0.9]}
)";

scene::Scene load(std::string_view text) {
    scene::LoadResult loaded = scene::load_scene_text(text, "s.yaml");
    EXPECT_TRUE(loaded.ok());
    return loaded.scene;
}

TEST(DebugDrawTest, ContactPointsCarryTheWeightsAtRest) {
    const scene::Scene scene = load(at_rest);
    Playback playback(scene);
    ASSERT_TRUE(playback.show(45, false));   // t = 1.5 s
    const physics::World& world = playback.world();
    const double g = 9.81;
    const double ball = std::numbers::pi * 0.25 * 0.25, crate = 0.24, lid = 0.06;   // kg
    double ball_force = 0, crate_force = 0;
    int ball_points = 0, crate_points = 0;
    for (const physics::ContactPoint& c : world.contact_points()) {
        if (c.other_kind != physics::ContactEvent::Other::wall) continue;
        if (c.a == 0) {   // the ball on the floor: under its centre, pushing down
            ++ball_points;
            ball_force += c.force;
            EXPECT_NEAR(c.point.x, 0.6, 1e-3);
            EXPECT_NEAR(c.point.y, 0.0, 1e-3);
            EXPECT_NEAR(c.normal.x, 0.0, 1e-6);
            EXPECT_NEAR(c.normal.y, -1.0, 1e-6);
        }
        if (c.a == 2) {   // the crate: its two bottom corners
            ++crate_points;
            crate_force += c.force;
            EXPECT_NEAR(std::abs(c.point.x - 1.5), 0.3, 1e-3);
            EXPECT_NEAR(c.point.y, 0.0, 1e-3);
        }
    }
    EXPECT_EQ(ball_points, 1);
    EXPECT_EQ(crate_points, 2);
    EXPECT_NEAR(ball_force, ball * g, 0.01 * ball * g);
    EXPECT_NEAR(crate_force, (crate + lid) * g, 0.01 * (crate + lid) * g);
    // At rest long enough: the ball, the crate and the lid sleep; the bob on its rod does not.
    const std::vector<bool> asleep = world.sleeping();
    ASSERT_EQ(asleep.size(), 4U);
    EXPECT_TRUE(asleep[0]);
    EXPECT_FALSE(asleep[1]);
    EXPECT_TRUE(asleep[2]);
    EXPECT_TRUE(asleep[3]);
}

TEST(DebugDrawTest, ADiscOnTheFloorHasOnePointUnderItWithItsWeight) {
    const scene::Scene scene = load(R"(version: 1
video: {size: [160, 90], fps: 30, duration: 1}
walls:
  - box: [[0, 0], [3.2, 1.8]]
discs:
  - {position: [1, 0.2], radius: 0.2}
)");
    Playback playback(scene);
    ASSERT_TRUE(playback.show(20, false));
    ASSERT_FALSE(playback.world().manifold_solver());
    const auto points = playback.world().contact_points();
    ASSERT_EQ(points.size(), 1U);
    EXPECT_EQ(points[0].other_kind, physics::ContactEvent::Other::wall);
    EXPECT_NEAR(points[0].point.x, 1.0, 1e-6);
    EXPECT_NEAR(points[0].point.y, 0.0, 1e-3);
    EXPECT_NEAR(points[0].normal.y, -1.0, 1e-9);
    const double weight = std::numbers::pi * 0.2 * 0.2 * 9.81;
    EXPECT_NEAR(points[0].force, weight, 0.01 * weight);
}

TEST(DebugDrawTest, OnlyWhatTheSceneAsksForIsDrawn) {
    std::string text(at_rest);
    text.replace(text.find("debug: [contacts, normals, impulses, boxes, joints, sleep]"),
                 std::string("debug: [contacts, normals, impulses, boxes, joints, sleep]").size(),
                 "debug: [contacts]");
    const scene::Scene scene = load(text);
    Playback playback(scene);
    auto view = playback.show(45, true);
    ASSERT_TRUE(view);
    // Contacts only: a dot (a line of no length) per point, in red; the fills as they are.
    const auto contacts = playback.world().contact_points().size();
    ASSERT_EQ((*view)->debug.size(), contacts);
    for (const render::LineGeom& dot : (*view)->debug) {
        EXPECT_EQ(dot.ax, dot.bx);
        EXPECT_EQ(dot.ay, dot.by);
        EXPECT_GT(dot.color.r, 0.9f);
    }
    EXPECT_EQ((*view)->discs[0].fill.r, static_cast<float>(0xf4) / 255);
    // None asked for: nothing drawn, nothing asked of the physics.
    const scene::Scene plain = load(std::string(at_rest).replace(
        std::string(at_rest).find("debug: [contacts, normals, impulses, boxes, joints, sleep]"),
        std::string("debug: [contacts, normals, impulses, boxes, joints, sleep]").size(),
        "outline: true"));
    Playback quiet(plain);
    view = quiet.show(45, true);
    ASSERT_TRUE(view);
    EXPECT_TRUE((*view)->debug.empty());
}

// Tolerance: golden_check.hpp's (a channel off by more than 2 in at most 0.1 % of the
// pixels), for Mesa versions' anti-aliasing; every debug line and dot moves hundreds.
TEST(DebugDrawGLTest, EverythingAtOnceMatchesItsGolden) {
    const scene::Scene scene = load(at_rest);
    Playback playback(scene);
    auto view = playback.show(45, true);
    ASSERT_TRUE(view);
    render::test::check_golden("debug_draw", **view, 320, 180);
}

}  // namespace
}  // namespace discreel::job

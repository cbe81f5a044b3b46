// Flicks and grabs.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

TEST(Throws, FlickSetsVelocityAtTheFirstStepStartingAtItsTime) {
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies.push_back(testing::disc({0, 0}, {0, 0}, 0.1, 1.0));
    ThrowDef flick;
    flick.body = 0;
    flick.at = 0.5;  // = step 240 at 480 Hz
    flick.velocity = Vec2{3, -2};
    def.throws.push_back(flick);
    World world(def);
    for (int k = 0; k < 240; ++k) world.step();
    EXPECT_EQ(world.bodies()[0].velocity.x, 0.0);
    world.step();
    EXPECT_EQ(world.bodies()[0].velocity.x, 3.0);
    EXPECT_EQ(world.bodies()[0].velocity.y, -2.0);
    EXPECT_NEAR(world.bodies()[0].position.x, 3.0 / 480, 1e-15);
}

WorldDef grab_scene() {
    WorldDef def;
    def.bodies.push_back(testing::disc({0, 0}, {0, 0}, 0.2, 1.0));
    ThrowDef grab;
    grab.body = 0;
    grab.path = {{0.25, {1, 1}}, {0.5, {2, 1}}, {0.75, {2, 3}}};
    def.throws.push_back(grab);
    return def;
}

TEST(Throws, GrabFollowsThePathIgnoringGravityAndReleasesWithItsVelocity) {
    WorldDef def = grab_scene();
    World world(def);
    testing::run_for(world, 0.375);  // halfway along the first segment
    EXPECT_NEAR(world.bodies()[0].position.x, 1.5, 1e-12);
    EXPECT_NEAR(world.bodies()[0].position.y, 1.0, 1e-12);
    EXPECT_NEAR(world.bodies()[0].velocity.x, 4.0, 1e-9);
    testing::run_for(world, 0.375);  // t = 0.75: the last point
    EXPECT_NEAR(world.bodies()[0].position.x, 2.0, 1e-12);
    EXPECT_NEAR(world.bodies()[0].position.y, 3.0, 1e-12);
    world.step();  // released, with the last segment's velocity (0, 8), then falls
    EXPECT_NEAR(world.bodies()[0].velocity.x, 0.0, 1e-12);
    EXPECT_NEAR(world.bodies()[0].velocity.y, 8.0 - 9.81 / 480, 1e-9);
}

TEST(Throws, GrabReleasesWithAnExplicitVelocity) {
    WorldDef def = grab_scene();
    def.throws[0].release = Vec2{-5, 0};
    World world(def);
    testing::run_for(world, 0.75 + 1.0 / 480);
    EXPECT_NEAR(world.bodies()[0].velocity.x, -5.0, 1e-12);
}

// A hand carrying disc 0 along the floor at 4 m/s into disc 1, letting go at t = 1 at rest.
WorldDef pushing_grab() {
    WorldDef def;
    const testing::Material material{.restitution = 0.2, .friction = 0.3};
    def.walls.push_back(testing::box({-5, 0}, {5, 5}, material));
    def.bodies.push_back(testing::disc({-3, 0.3}, {0, 0}, 0.3, 1.0, material));
    def.bodies.push_back(testing::disc({0, 0.3}, {0, 0}, 0.3, 1.0, material));
    ThrowDef grab;
    grab.body = 0;
    grab.path = {{0.0, {-3, 0.3}}, {1.0, {1, 0.3}}};
    grab.release = Vec2{0, 0};
    def.throws.push_back(grab);
    return def;
}

TEST(Throws, HeldDiscPushesOthersOutOfItsWay) {
    World world(pushing_grab());
    testing::run_for(world, 1.0);
    const auto& d = world.bodies();
    EXPECT_NEAR(d[0].position.x, 1.0, 1e-12);
    // The pushed disc is ahead of the hand, not overlapped by it.
    EXPECT_GE(d[1].position.x - d[0].position.x, 0.6 - 1e-3);
}

// The same hand lets go at t = 1 with the disc on the floor, at rest: its contacts get its mass
// back at the release (held, it had none to the solver; with the contacts' masses kept from
// then, its row against the floor was infinitely heavy and the state stopped being finite).
// It stays where it was let go; the disc it pushed slides on, on the floor.
TEST(Throws, ADiscReleasedOnTheFloorRestsThere) {
    World world(pushing_grab());
    testing::run_for(world, 1.5);
    ASSERT_FALSE(world.failure());
    for (const BodyState& d : world.bodies()) EXPECT_NEAR(d.position.y, 0.3, 1e-3);
    const BodyState& released = world.bodies()[0];
    EXPECT_NEAR(released.position.x, 1.0, 1e-3);
    EXPECT_LT(std::hypot(released.velocity.x, released.velocity.y), 1e-3);
}

// A box held still on the floor for a second, then let go at rest: held, it had no contact
// with the floor (two bodies a contact cannot move make none), and the steps kept their
// contacts, nothing moving; the release makes them again, so it rests where it was let go.
TEST(Throws, ABoxHeldStillOnTheFloorAndLetGoRestsThere) {
    WorldDef def;
    const testing::Material material{.restitution = 0.2, .friction = 0.5};
    def.walls.push_back(testing::box({-5, 0}, {5, 5}, material));
    def.bodies.push_back(testing::body(*box_shape(1, 1), {0, 0.5}, 1.0, material));
    ThrowDef grab;
    grab.body = 0;
    grab.path = {{0.0, {0, 0.5}}, {1.0, {0, 0.5}}};
    grab.release = Vec2{0, 0};
    def.throws.push_back(grab);
    World world(def);
    testing::run_for(world, 1.0);
    double lowest = world.bodies()[0].position.y;
    for (int k = 0; k < 480; ++k) {
        world.step();
        lowest = std::min(lowest, world.bodies()[0].position.y);
    }
    EXPECT_GT(lowest, 0.5 - 1e-5);
    EXPECT_NEAR(world.bodies()[0].position.y, 0.5, 1e-5);
}

// The case: a disc at (1, 1) grabbed with a path starting at t = 0.5 at (3, 3). The hand
// holds it from t = 0 and carries it in a straight line to the first waypoint, arriving on time.
TEST(Throws, GrabCarriesTheDiscToItsFirstWaypointWithoutAJump) {
    WorldDef def;
    def.bodies.push_back(testing::disc({1, 1}, {0, 0}, 0.2, 1.0));
    ThrowDef grab;
    grab.body = 0;
    grab.path = {{0.5, {3, 3}}, {1.0, {4, 3}}};
    def.throws.push_back(grab);
    World world(def);
    double farthest = 0;   // the largest move in one step, metres
    for (int k = 0; k < 480; ++k) {
        const Vec2 before = world.bodies()[0].position;
        world.step();
        const Vec2 after = world.bodies()[0].position;
        farthest = std::max(farthest, std::hypot(after.x - before.x, after.y - before.y));
        if (k + 1 == 120) {   // t = 0.25: halfway to the first waypoint, not fallen
            EXPECT_NEAR(after.x, 2.0, 1e-12);
            EXPECT_NEAR(after.y, 2.0, 1e-12);
        }
        if (k + 1 == 240) {   // t = 0.5: at the first waypoint
            EXPECT_NEAR(after.x, 3.0, 1e-12);
            EXPECT_NEAR(after.y, 3.0, 1e-12);
        }
    }
    // The fastest leg is the carry: 2.83 m in 0.5 s, 5.9 mm per step at 480 Hz.
    EXPECT_LT(farthest, std::hypot(2.0, 2.0) / 0.5 / 480 + 1e-9);
}

TEST(Throws, GrabStartingAtTimeZeroPlacesTheDiscOnItsFirstWaypoint) {
    WorldDef def;
    def.bodies.push_back(testing::disc({1, 1}, {2, 0}, 0.2, 1.0));
    ThrowDef grab;
    grab.body = 0;
    grab.path = {{0.0, {3, 3}}, {1.0, {4, 3}}};
    def.throws.push_back(grab);
    World world(def);
    EXPECT_EQ(world.bodies()[0].position.x, 3.0);   // the state frame 0 shows
    EXPECT_EQ(world.bodies()[0].position.y, 3.0);
}

}  // namespace
}  // namespace discreel::physics

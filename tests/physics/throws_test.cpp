// Flicks and grabs.
#include <cmath>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

TEST(Throws, FlickSetsVelocityAtTheFirstStepStartingAtItsTime) {
    WorldDef def;
    def.gravity = {0, 0};
    def.discs.push_back(testing::disc({0, 0}, {0, 0}, 0.1, 1.0));
    ThrowDef flick;
    flick.disc = 0;
    flick.at = 0.5;  // = step 240 at 480 Hz
    flick.velocity = Vec2{3, -2};
    def.throws.push_back(flick);
    World world(def);
    for (int k = 0; k < 240; ++k) world.step();
    EXPECT_EQ(world.discs()[0].velocity.x, 0.0);
    world.step();
    EXPECT_EQ(world.discs()[0].velocity.x, 3.0);
    EXPECT_EQ(world.discs()[0].velocity.y, -2.0);
    EXPECT_NEAR(world.discs()[0].position.x, 3.0 / 480, 1e-15);
}

WorldDef grab_scene() {
    WorldDef def;
    def.discs.push_back(testing::disc({0, 0}, {0, 0}, 0.2, 1.0));
    ThrowDef grab;
    grab.disc = 0;
    grab.path = {{0.25, {1, 1}}, {0.5, {2, 1}}, {0.75, {2, 3}}};
    def.throws.push_back(grab);
    return def;
}

TEST(Throws, GrabFollowsThePathIgnoringGravityAndReleasesWithItsVelocity) {
    WorldDef def = grab_scene();
    World world(def);
    testing::run_for(world, 0.375);  // halfway along the first segment
    EXPECT_NEAR(world.discs()[0].position.x, 1.5, 1e-12);
    EXPECT_NEAR(world.discs()[0].position.y, 1.0, 1e-12);
    EXPECT_NEAR(world.discs()[0].velocity.x, 4.0, 1e-9);
    testing::run_for(world, 0.375);  // t = 0.75: the last point
    EXPECT_NEAR(world.discs()[0].position.x, 2.0, 1e-12);
    EXPECT_NEAR(world.discs()[0].position.y, 3.0, 1e-12);
    world.step();  // released, with the last segment's velocity (0, 8), then falls
    EXPECT_NEAR(world.discs()[0].velocity.x, 0.0, 1e-12);
    EXPECT_NEAR(world.discs()[0].velocity.y, 8.0 - 9.81 / 480, 1e-9);
}

TEST(Throws, GrabReleasesWithAnExplicitVelocity) {
    WorldDef def = grab_scene();
    def.throws[0].release = Vec2{-5, 0};
    World world(def);
    testing::run_for(world, 0.75 + 1.0 / 480);
    EXPECT_NEAR(world.discs()[0].velocity.x, -5.0, 1e-12);
}

TEST(Throws, HeldDiscPushesOthersOutOfItsWay) {
    WorldDef def;
    const testing::Material material{.restitution = 0.2, .friction = 0.3};
    def.walls.push_back(testing::box({-5, 0}, {5, 5}, material));
    def.discs.push_back(testing::disc({-3, 0.3}, {0, 0}, 0.3, 1.0, material));
    def.discs.push_back(testing::disc({0, 0.3}, {0, 0}, 0.3, 1.0, material));
    ThrowDef grab;
    grab.disc = 0;
    grab.path = {{0.0, {-3, 0.3}}, {1.0, {1, 0.3}}};
    grab.release = Vec2{0, 0};
    def.throws.push_back(grab);
    World world(def);
    testing::run_for(world, 1.0);
    const auto& d = world.discs();
    EXPECT_NEAR(d[0].position.x, 1.0, 1e-12);
    // The pushed disc is ahead of the hand, not overlapped by it.
    EXPECT_GE(d[1].position.x - d[0].position.x, 0.6 - 1e-3);
}

}  // namespace
}  // namespace discreel::physics

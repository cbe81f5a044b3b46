// Continuous collision: fast discs never pass through walls.
#include <cmath>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::disc;

// A closed square of four 2 cm segments around the origin; a disc at 500 m/s (0.52 m per
// substep, 26 wall thicknesses) must stay inside for a second of bouncing.
TEST(Continuous, FastDiscStaysInsideThinWalls) {
    const double half = 1.0, t = 0.02, r = 0.05;
    WorldDef def;
    def.gravity = {0, -9.81};
    def.walls = {testing::segment({-half, -half}, {half, -half}, t),
                 testing::segment({half, -half}, {half, half}, t),
                 testing::segment({half, half}, {-half, half}, t),
                 testing::segment({-half, half}, {-half, -half}, t)};
    def.bodies.push_back(disc({0, 0}, {500 * std::cos(0.3), 500 * std::sin(0.3)}, r, 1.0));
    World world(def);
    const double limit = half - t / 2 - r + 1e-6;
    for (int k = 0; k < 480; ++k) {
        world.step();
        const BodyState& s = world.bodies()[0];
        ASSERT_LT(std::abs(s.position.x), limit) << "step " << k;
        ASSERT_LT(std::abs(s.position.y), limit) << "step " << k;
    }
    EXPECT_GT(std::hypot(world.bodies()[0].velocity.x, world.bodies()[0].velocity.y), 450.0);
}

TEST(Continuous, FastDiscStaysInsideABox) {
    WorldDef def;
    def.walls.push_back(testing::box({0, 0}, {1, 1}));
    def.bodies.push_back(disc({0.5, 0.5}, {-300, 500}, 0.05, 1.0));
    World world(def);
    for (int k = 0; k < 480; ++k) {
        world.step();
        const BodyState& s = world.bodies()[0];
        ASSERT_GE(s.position.x, 0.05 - 1e-6);
        ASSERT_LE(s.position.x, 0.95 + 1e-6);
        ASSERT_GE(s.position.y, 0.05 - 1e-6);
        ASSERT_LE(s.position.y, 0.95 + 1e-6);
    }
}

TEST(Continuous, FastDiscBouncesOffASingleThinSegment) {
    WorldDef def;
    def.gravity = {0, 0};
    def.walls.push_back(testing::segment({1, -1}, {1, 1}, 0.02));
    def.bodies.push_back(disc({0, 0.3}, {500, 0}, 0.01, 1.0));
    World world(def);
    testing::run_for(world, 0.05);
    EXPECT_NEAR(world.bodies()[0].velocity.x, -500.0, 1e-9);
    EXPECT_LT(world.bodies()[0].position.x, 1.0);
}

TEST(Continuous, FastDiscDoesNotSkipAPeg) {
    WorldDef def;
    def.gravity = {0, 0};
    BodyDef peg = disc({1, 0}, {0, 0}, 0.01, 1.0);
    peg.is_static = true;
    def.bodies = {disc({0, 0}, {400, 0}, 0.01, 1.0), peg};
    World world(def);
    testing::run_for(world, 0.05);
    EXPECT_NEAR(world.bodies()[0].velocity.x, -400.0, 1e-9);
    EXPECT_EQ(world.bodies()[1].position.x, 1.0);
}

// A 10 cm box at 300 m/s (0.625 m, 12.5 of its half-widths per step), thrown a little
// upwards and spinning, between a box wall and a 2 cm segment 2 m away, under gravity, for a
// second: it never passes the thin wall or leaves the box, and (e = 1, no friction) keeps its
// energy. Its corners strike first, so each bounce turns some of its speed into spin and
// height: it crosses back and forth less often than the 150 times flight straight across gives.
TEST(Continuous, FastBoxStaysBetweenAWallAndAThinWall) {
    WorldDef def;
    def.gravity = {0, -9.81};
    def.walls = {testing::box({-1, -1}, {3, 1}), testing::segment({1, -1}, {1, 1}, 0.02)};
    BodyDef box = testing::body(*box_shape(0.1, 0.1), {0, 0});
    box.velocity = {300, 5};
    box.angular_velocity = 40;
    def.bodies.push_back(box);
    World world(def);
    const double start = world.energy();
    int reversals = 0;
    double previous = 300;
    for (int k = 0; k < def.rate; ++k) {
        world.step();
        const BodyState& s = world.bodies()[0];
        ASSERT_GT(s.position.x, -1.0) << "step " << k;
        ASSERT_LT(s.position.x, 0.99) << "step " << k;
        ASSERT_GT(s.position.y, -1.0) << "step " << k;
        ASSERT_LT(s.position.y, 1.0) << "step " << k;
        reversals += (s.velocity.x > 0) != (previous > 0) ? 1 : 0;
        previous = s.velocity.x;
    }
    EXPECT_NEAR(world.energy(), start, 0.01 * start);
    EXPECT_GT(reversals, 50);   // still bouncing between the two (84 measured)
}

}  // namespace
}  // namespace discreel::physics

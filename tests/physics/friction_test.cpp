// Coulomb friction turns sliding into rolling: with no spin at first, a disc of inertia
// m r^2 / 2 sliding at v0 keeps angular momentum about the contact point, so it rolls at
// v = 2/3 v0 from t = v0 / (3 mu g) on.
#include <cmath>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

TEST(Friction, SlidingDiscEndsRollingAtTwoThirdsSpeed) {
    const double g = 9.81, mu = 0.3, v0 = 3.0, r = 0.5;
    WorldDef def;
    const testing::Material rough{.restitution = 0.0, .friction = mu};
    def.walls.push_back(testing::box({0, 0}, {100, 10}, rough));
    def.bodies.push_back(testing::disc({1, r}, {v0, 0}, r, 1.0, rough));
    World world(def);
    double rolling_from = -1.0;
    for (int k = 0; k < 480 * 2 && rolling_from < 0; ++k) {
        world.step();
        const BodyState& s = world.bodies()[0];
        // Clockwise spin rolls to the right: v = -omega r.
        if (std::abs(s.velocity.x + s.angular_velocity * r) < 1e-9) rolling_from = world.time();
    }
    ASSERT_GT(rolling_from, 0.0) << "never rolled";
    const double t_roll = v0 / (3 * mu * g);
    EXPECT_NEAR(rolling_from, t_roll, 0.02 * t_roll);
    const BodyState& s = world.bodies()[0];
    EXPECT_NEAR(s.velocity.x, 2.0 / 3.0 * v0, 0.01 * 2.0 / 3.0 * v0);
    EXPECT_NEAR(-s.angular_velocity * r, s.velocity.x, 1e-9);
    // Rolling without slipping costs nothing: it keeps going.
    testing::run_for(world, 1.0);
    EXPECT_NEAR(world.bodies()[0].velocity.x, 2.0 / 3.0 * v0, 0.01 * 2.0 / 3.0 * v0);
}

TEST(Friction, SpinningDiscOnIceKeepsSpinning) {
    WorldDef def;
    const testing::Material ice{.restitution = 0.0, .friction = 0.0};
    def.walls.push_back(testing::box({0, 0}, {10, 10}, ice));
    BodyDef d = testing::disc({5, 0.5}, {0, 0}, 0.5, 1.0, ice);
    d.angular_velocity = 10.0;
    def.bodies.push_back(d);
    World world(def);
    testing::run_for(world, 1.0);
    EXPECT_EQ(world.bodies()[0].angular_velocity, 10.0);
    EXPECT_EQ(world.bodies()[0].velocity.x, 0.0);
}

}  // namespace
}  // namespace discreel::physics

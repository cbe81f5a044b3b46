// A disc against the floor: rebound height, rest, and free flight, against closed forms.
#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::disc;
constexpr double g = 9.81;

// Steps `world` (at most 10 s) until its body 0, a ball of radius r dropped on a floor at
// y = 0, has bounced and flies up clear of the floor; from there the flight is ballistic, so
// the apex above the floor follows from the state (m). Nothing if it never bounces.
std::optional<double> apex_after_bounce(World& world, double r) {
    for (int k = 0; k < 480 * 10; ++k) {
        world.step();
        const BodyState& s = world.bodies()[0];
        if (s.velocity.y > 0.0 && s.position.y > r) {
            return s.position.y + s.velocity.y * s.velocity.y / (2 * g) - r;
        }
    }
    return std::nullopt;
}

class Rebound : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(Rebound, ReachesRestitutionSquaredTimesDropHeight) {
    const auto [e, drop] = GetParam();
    const double r = 0.1;
    WorldDef def;
    def.walls.push_back(testing::box({-1, 0}, {1, 30}, {.restitution = e}));
    def.bodies.push_back(disc({0, r + drop}, {0, 0}, r, 1.0, {.restitution = e}));
    World world(def);
    // The disc's flight is the exact parabola in this integrator.
    const std::optional<double> apex = apex_after_bounce(world, r);
    ASSERT_TRUE(apex.has_value());
    EXPECT_NEAR(*apex, e * e * drop, 0.02 * e * e * drop);
}

INSTANTIATE_TEST_SUITE_P(RestitutionsAndHeights, Rebound,
                         ::testing::Combine(::testing::Values(0.3, 0.5, 0.8, 1.0),
                                            ::testing::Values(0.01, 0.1, 1.0, 10.0)));

// The same drops of a circle shape and of a box landing flat (the manifold solver): the
// bounce off the floor is timed within the step, as the disc's impact is, so the rebound is
// e^2 h to the rounding of the flight (at the step's end, the 1 cm drop rose 3 % too high).
class ShapeRebound : public ::testing::TestWithParam<std::tuple<bool, double, double>> {};

TEST_P(ShapeRebound, ReachesRestitutionSquaredTimesDropHeight) {
    const auto [box, e, drop] = GetParam();
    const double r = 0.1;
    WorldDef def;
    def.walls.push_back(testing::box({-1, 0}, {1, 30}, {.restitution = e}));
    const Shape shape = box ? *box_shape(2 * r, 2 * r) : circle_shape(r);
    def.bodies.push_back(testing::body(shape, {0, r + drop}, 1.0, {.restitution = e}));
    World world(def);
    ASSERT_TRUE(world.manifold_solver());
    const std::optional<double> apex = apex_after_bounce(world, r);
    ASSERT_TRUE(apex.has_value());
    EXPECT_NEAR(*apex, e * e * drop, 1e-6 * drop);
    // A flat landing gives no spin (to rounding: the box's corners are not exactly level).
    EXPECT_NEAR(world.bodies()[0].angular_velocity, 0.0, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Bounce, ShapeRebound,
                         ::testing::Combine(::testing::Bool(), ::testing::Values(0.3, 0.5, 1.0),
                                            ::testing::Values(0.01, 0.1, 1.0, 10.0)));

// A circle shape spinning as it lands is measured by its centre, not by a point of its rim
// that turned with it: at 150 rad/s its rim's point rose 19 mm off the floor in a step, the
// circle counted as apart, and it was left 16 mm deep in the floor.
TEST(Bounce, ASpinningCircleShapeLandsWithoutSinkingIn) {
    for (const double spin : {0.0, 50.0, 150.0, 300.0}) {
        SCOPED_TRACE(spin);
        const double r = 0.4;
        WorldDef def;
        def.walls.push_back(testing::box({-50, 0}, {50, 30}, {.restitution = 0.5, .friction = 0.5}));
        BodyDef d = testing::body(circle_shape(r), {0, 0.5}, 1.0, {.restitution = 0.5, .friction = 0.5});
        d.velocity = {0, -10};
        d.angular_velocity = spin;
        def.bodies.push_back(d);
        World world(def);
        double deepest = 0;   // m
        for (int k = 0; k < 480; ++k) {
            world.step();
            deepest = std::max(deepest, r - world.bodies()[0].position.y);
        }
        EXPECT_LT(deepest, 5e-4);   // the manifold solver's slop
    }
}

// An elastic ball keeps bouncing to the height it fell from: a disc, and a circle shape (the
// manifold solver, whose bounce off the floor is timed within the step; bounced at the step's
// end it kept 96 % of the height after 10 s).
class ElasticBall : public ::testing::TestWithParam<bool> {};

TEST_P(ElasticBall, KeepsBouncingToTheSameHeight) {
    const bool shape = GetParam();
    const double r = 0.1, drop = 1.0;
    WorldDef def;
    def.walls.push_back(testing::box({-1, 0}, {1, 30}, {.restitution = 1.0}));
    def.bodies.push_back(shape ? testing::body(circle_shape(r), {0, r + drop}, 1.0, {.restitution = 1.0})
                               : disc({0, r + drop}, {0, 0}, r, 1.0, {.restitution = 1.0}));
    World world(def);
    ASSERT_EQ(world.manifold_solver(), shape);
    double highest_late = 0.0;
    for (int k = 0; k < 480 * 10; ++k) {
        world.step();
        if (k > 480 * 9) highest_late = std::max(highest_late, world.bodies()[0].position.y - r);
    }
    // Sampled apex: within g (dt/2)^2 / 2 = 1.1e-5 m of the true one.
    EXPECT_NEAR(highest_late, drop, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Bounce, ElasticBall, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                             return info.param ? "CircleShape" : "Disc";
                         });

TEST(Bounce, RestingDiscStaysPutForTenSeconds) {
    WorldDef def;
    def.walls.push_back(testing::box({0, 0}, {4, 4}, {.restitution = 0.5, .friction = 0.6}));
    def.bodies.push_back(disc({2, 0.3}, {0, 0}, 0.3, 2.0, {.restitution = 0.5, .friction = 0.6}));
    World world(def);
    testing::run_for(world, 10.0);
    const BodyState& s = world.bodies()[0];
    EXPECT_LT(std::hypot(s.position.x - 2, s.position.y - 0.3), 1e-5);
    EXPECT_LT(std::hypot(s.velocity.x, s.velocity.y), 1e-6);
}

// A disc, and a box (the manifold solver's world): both fly the exact parabola, not one
// lagging half a step behind it (g t dt / 2: 1 cm after 1 s).
class FreeFlight : public ::testing::TestWithParam<bool> {};

TEST_P(FreeFlight, FollowsTheParabolaAndKeepsItsSpin) {
    const bool box = GetParam();
    WorldDef def;
    def.gravity = {0.5, -g};
    BodyDef d = box ? testing::body(*box_shape(0.3, 0.2), {1, 2}) : disc({1, 2}, {3, 7}, 0.2, 1.0);
    d.velocity = {3, 7};
    d.angular_velocity = 200.0;
    def.bodies.push_back(d);
    World world(def);
    ASSERT_EQ(world.manifold_solver(), box);
    for (int k = 1; k <= 480 * 2; ++k) {
        world.step();
        const double t = world.time();
        const BodyState& s = world.bodies()[0];
        ASSERT_NEAR(s.position.x, 1 + 3 * t + 0.25 * t * t, 1e-9) << t;
        ASSERT_NEAR(s.position.y, 2 + 7 * t - 0.5 * g * t * t, 1e-9) << t;
        ASSERT_NEAR(s.velocity.y, 7 - g * t, 1e-9) << t;
        ASSERT_EQ(s.angular_velocity, 200.0);
        ASSERT_NEAR(s.angle, 200.0 * t, 1e-9) << t;
    }
}

INSTANTIATE_TEST_SUITE_P(Bounce, FreeFlight, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                             return info.param ? "Box" : "Disc";
                         });

// Two boxes dropped one on the other fall together along the parabola: each moves by its mean
// velocity, the upper one no more than the lower (moved by the mean alone, it rose g dt^2 / 2
// a step off the lower one, 1 cm in a second).
TEST(Bounce, AStackFallingTogetherStaysTogether) {
    WorldDef def;
    def.walls.push_back(testing::box({-10, 0}, {10, 40}));
    def.bodies = {testing::body(*box_shape(1, 1), {0, 20.5}), testing::body(*box_shape(1, 1), {0, 21.5})};
    World world(def);
    for (int k = 1; k <= 480; ++k) {
        world.step();
        const double t = world.time();
        ASSERT_NEAR(world.bodies()[0].position.y, 20.5 - 0.5 * g * t * t, 1e-9) << t;
        ASSERT_NEAR(world.bodies()[1].position.y - world.bodies()[0].position.y, 1.0, 1e-9) << t;
    }
}

// Angles are integrated and never limited per step (some engines clamp rotation to an eighth
// of a turn per step, Box2D v3.2 among them), so 2 000 rad/s (4.2 rad per 480 Hz step) is kept
// exactly.
TEST(Bounce, SpinOfMoreThanAnEighthTurnPerStepIsKept) {
    WorldDef def;
    BodyDef d = disc({1, 2}, {0, 0}, 0.2, 1.0);
    d.angular_velocity = 2000.0;
    def.bodies.push_back(d);
    World world(def);
    const double eighth_turn = 3.141592653589793 / 4;  // rad
    ASSERT_GT(2000.0 / def.rate, 5 * eighth_turn);
    for (int k = 1; k <= 480; ++k) {
        world.step();
        const BodyState& s = world.bodies()[0];
        ASSERT_EQ(s.angular_velocity, 2000.0);
        ASSERT_NEAR(s.angle, 2000.0 * world.time(), 1e-12 * 2000.0 * world.time()) << k;
    }
}

}  // namespace
}  // namespace discreel::physics

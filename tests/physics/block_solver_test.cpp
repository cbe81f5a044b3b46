// The two-point block solve against what Newton's laws give in one step: a flat landing
// rebounds at e times its speed with no spin, even when the points are not symmetric about the
// centre of mass; a tilted landing pushes only at the point that closes; friction takes
// exactly mu times the normal impulse off a sliding box.
#include <cmath>

#include <gtest/gtest.h>

#include "block_solver.hpp"

namespace discreel::physics::detail {
namespace {

// A 1 kg box, 1 m x 0.5 m, over static ground (body A, which never moves).
BlockBody box(V2 v, double omega = 0) {
    return {.v = v, .omega = omega, .inv_mass = 1.0, .inv_inertia = 12.0 / (1.0 + 0.25)};
}

BlockContact two_points(double left, double right) {
    BlockContact c;
    c.normal = V2(0, 1);
    c.count = 2;
    // The points are on the ground's surface; rb from the box's centre, 0.25 m above it.
    c.points[0].ra = V2(left, 0);
    c.points[0].rb = V2(left, -0.25);
    c.points[1].ra = V2(right, 0);
    c.points[1].rb = V2(right, -0.25);
    return c;
}

TEST(BlockSolverTest, FlatLandingReboundsWithoutSpinInOneIteration) {
    for (const auto& [left, right] : {std::pair{-0.5, 0.5}, std::pair{-0.2, 0.5}}) {
        BlockBody ground;
        BlockBody b = box(V2(0, -2));
        BlockContact c = two_points(left, right);
        prepare_block(c, ground, b);
        set_restitution_targets(c, ground, b, 0.5);
        solve_block(c, ground, b);
        EXPECT_NEAR(b.v.y(), 1.0, 1e-12) << left;   // e * 2 m/s
        EXPECT_NEAR(b.v.x(), 0.0, 1e-12);
        EXPECT_NEAR(b.omega, 0.0, 1e-12) << left;   // no spin from a flat landing
        EXPECT_NEAR(c.points[0].normal_impulse + c.points[1].normal_impulse, 3.0, 1e-12);
        // Solved: another iteration changes nothing.
        const BlockBody before = b;
        solve_block(c, ground, b);
        EXPECT_NEAR(b.v.y(), before.v.y(), 1e-12);
        EXPECT_NEAR(b.omega, before.omega, 1e-12);
    }
}

// Falling and turning so that the right point closes faster than the box falls and the left one
// rises: only the right point pushes (the second case of the four), and after the solve the right
// point moves at its target while the left one separates.
TEST(BlockSolverTest, OnlyTheClosingPointPushes) {
    BlockBody ground;
    BlockBody b = box(V2(0, -0.5), -3.0);   // clockwise: the right end goes down
    BlockContact c = two_points(-0.5, 0.5);
    // Left point: -0.5 + (-3)(-(-0.5))... its normal velocity is v.y + omega * x = -0.5 + 1.5.
    EXPECT_NEAR(normal_velocity(c, c.points[0], ground, b), 1.0, 1e-12);
    EXPECT_NEAR(normal_velocity(c, c.points[1], ground, b), -2.0, 1e-12);
    prepare_block(c, ground, b);
    set_restitution_targets(c, ground, b, 0.0);
    solve_block(c, ground, b);
    EXPECT_EQ(c.points[0].normal_impulse, 0.0);
    EXPECT_GT(c.points[1].normal_impulse, 0.0);
    EXPECT_NEAR(normal_velocity(c, c.points[1], ground, b), 0.0, 1e-12);
    EXPECT_GT(normal_velocity(c, c.points[0], ground, b), 0.0);
}

// A box sliding at 3 m/s, pressed on the ground by one step of gravity at 480 Hz: friction
// takes mu g dt off its speed, and the normal impulses shift to the front point so that the
// friction's torque does not tip it.
TEST(BlockSolverTest, FrictionTakesMuTimesTheNormalImpulse) {
    const double g_dt = 9.81 / 480;
    BlockBody ground;
    BlockBody b = box(V2(3, -g_dt));
    BlockContact c = two_points(-0.5, 0.5);
    c.friction = 0.5;
    prepare_block(c, ground, b);
    set_restitution_targets(c, ground, b, 0.0);
    for (int i = 0; i < 20; ++i) solve_block(c, ground, b);
    EXPECT_NEAR(b.v.x(), 3 - 0.5 * g_dt, 1e-9);
    EXPECT_NEAR(b.v.y(), 0.0, 1e-9);
    EXPECT_NEAR(b.omega, 0.0, 1e-9);
    EXPECT_GT(c.points[1].normal_impulse, c.points[0].normal_impulse);   // the leading edge
}

}  // namespace
}  // namespace discreel::physics::detail

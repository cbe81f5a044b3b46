// Fast against fast: moving discs meet at their exact time of impact, whatever their speeds,
// and a disc sped up by an impact meets what it can then reach within the same step.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::disc;

class HeadOn : public ::testing::TestWithParam<double> {};

// Two 5 cm discs closing at 2 v, no walls: at 500 m/s each covers 21 radii per step. They meet
// inside a step, swap velocities exactly (equal masses, e = 1) and never pass each other.
TEST_P(HeadOn, DiscsSwapVelocitiesAndNeverPassEachOther) {
    const double v = GetParam();
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies = {disc({-1.0, 0}, {v, 0}, 0.05, 1.0), disc({1.0, 0}, {-v, 0}, 0.05, 1.0)};
    World world(def);
    for (int k = 0; k < 20; ++k) {
        world.step();
        ASSERT_LT(world.bodies()[0].position.x, world.bodies()[1].position.x) << "step " << k;
    }
    EXPECT_EQ(world.bodies()[0].velocity.x, -v);
    EXPECT_EQ(world.bodies()[1].velocity.x, v);
    // Apart by the distance they have flown since their exact time of impact, 0.95 / v s.
    const double flown = 2 * v * (20.0 / def.rate - 0.95 / v);
    EXPECT_NEAR(world.bodies()[1].position.x - world.bodies()[0].position.x, 0.1 + flown,
                1e-12 * flown);
}

INSTANTIATE_TEST_SUITE_P(Speeds, HeadOn, ::testing::Values(30.0, 500.0, 1000.0));

// The same pair as circle shapes (the manifold solver): its impact is carried from where the
// advancement stopped, up to 0.25 mm short, to where the circles touch, so they end as far
// apart as the discs (they ended 0.25 mm further).
class CirclesHeadOn : public ::testing::TestWithParam<double> {};

TEST_P(CirclesHeadOn, SwapVelocitiesAndEndApartByWhatTheyFlew) {
    const double v = GetParam();
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies = {testing::body(circle_shape(0.05), {-1.0, 0}), testing::body(circle_shape(0.05), {1.0, 0})};
    def.bodies[0].velocity = {v, 0};
    def.bodies[1].velocity = {-v, 0};
    World world(def);
    ASSERT_TRUE(world.manifold_solver());
    for (int k = 0; k < 20; ++k) {
        world.step();
        ASSERT_LT(world.bodies()[0].position.x, world.bodies()[1].position.x) << "step " << k;
    }
    EXPECT_NEAR(world.bodies()[0].velocity.x, -v, 1e-12 * v);
    EXPECT_NEAR(world.bodies()[1].velocity.x, v, 1e-12 * v);
    const double flown = 2 * v * (20.0 / def.rate - 0.95 / v);
    EXPECT_NEAR(world.bodies()[1].position.x - world.bodies()[0].position.x, 0.1 + flown,
                1e-9 * flown);
}

INSTANTIATE_TEST_SUITE_P(Speeds, CirclesHeadOn, ::testing::Values(30.0, 500.0, 1000.0));

// A spaced row of five still discs, 10 radii apart, struck at 300 m/s (12.5 radii per step).
// Each disc is sped up by an impact in the middle of a step and reaches the next within it; the
// broad phase listed that pair when the struck disc was still at rest. The hit travels down the
// row exactly: the last disc leaves at 300 m/s, the others stop, and no disc passes another.
TEST(FastPairs, AStruckDiscMeetsTheDiscsItThenReaches) {
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies.push_back(disc({-1.0, 0}, {300, 0}, 0.05, 1.0));
    for (int k = 0; k < 5; ++k) def.bodies.push_back(disc({0.5 * k, 0}, {0, 0}, 0.05, 1.0));
    World world(def);
    for (int k = 0; k < 40; ++k) {
        world.step();
        for (std::size_t i = 0; i + 1 < world.bodies().size(); ++i) {
            ASSERT_LE(world.bodies()[i].position.x + 0.1, world.bodies()[i + 1].position.x + 1e-12)
                << "discs " << i << " and " << i + 1 << " at step " << k;
        }
    }
    for (std::size_t i = 0; i + 1 < world.bodies().size(); ++i) {
        EXPECT_EQ(world.bodies()[i].velocity.x, 0.0) << i;
    }
    EXPECT_EQ(world.bodies().back().velocity.x, 300.0);
}

// An elastic gas of 300 discs of 5 cm, all at the same speed in random directions, in a box:
// at 30 m/s each covers 1.25 radii per step. Overlap stays under 5 % of a radius and the energy
// within 2 % (the bounds of the requirement; measured: no overlap, energy to 1e-13).
class FastGas : public ::testing::TestWithParam<double> {};

TEST_P(FastGas, NeitherOverlapsNorChangesItsEnergy) {
    const double speed = GetParam(), r = 0.05;
    WorldDef def = testing::pile({.count = 300,
                                  .radius = r,
                                  .spacing = 0.2,
                                  .material = {.restitution = 1.0, .friction = 0.0},
                                  .gravity = {0, 0},
                                  .seed = 5});
    testing::Rng rng(9);
    for (BodyDef& d : def.bodies) {
        const double angle = rng.uniform(0, 2 * 3.141592653589793);
        d.velocity = {speed * std::cos(angle), speed * std::sin(angle)};
    }
    World world(def);
    const double start = world.energy();
    double deepest = 0;  // overlap of any pair after any step, in radii
    for (int k = 0; k < def.rate; ++k) {
        world.step();
        const auto discs = world.bodies();
        for (std::size_t i = 0; i < discs.size(); ++i) {
            for (std::size_t j = i + 1; j < discs.size(); ++j) {
                const double dx = discs[i].position.x - discs[j].position.x;
                const double dy = discs[i].position.y - discs[j].position.y;
                deepest = std::max(deepest, (2 * r - std::sqrt(dx * dx + dy * dy)) / r);
            }
        }
    }
    EXPECT_LT(deepest, 0.05);
    EXPECT_NEAR(world.energy(), start, 0.02 * start);
}

INSTANTIATE_TEST_SUITE_P(Speeds, FastGas, ::testing::Values(30.0));

}  // namespace
}  // namespace discreel::physics

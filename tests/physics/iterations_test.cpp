// WorldDef::iterations: how many sequential-impulse iterations the resting stage runs per
// substep. Gauss-Seidel on a stack converges slowly, so a tall column sinks into itself a
// little every substep and the projection pushes it back; more iterations leave it less to do.
#include <algorithm>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

// 40 discs stacked in a chimney barely wider than one, settled for 3 s: the deepest overlap
// (fraction of the radius) over the last second.
double column_overlap(int iterations) {
    WorldDef def;
    def.iterations = iterations;
    const testing::Material material{.restitution = 0.0, .friction = 0.5};
    def.walls.push_back(testing::box({0, 0}, {1.01, 60}, material));
    for (int k = 0; k < 40; ++k) {
        def.bodies.push_back(testing::disc({0.505, 0.5 + 1.0 * k}, {0, 0}, 0.5, 1.0, material));
    }
    World world(def);
    double worst = 0.0;
    for (int k = 0; k < 3 * def.rate; ++k) {
        world.step();
        if (k >= 2 * def.rate) worst = std::max(worst, world.stats().max_overlap_ratio);
    }
    return worst;
}

TEST(Iterations, MoreHoldAColumnTighter) {
    const double one = column_overlap(1);
    const double three = column_overlap(3);
    const double ten = column_overlap(10);
    // Each step up converges a stack much further; a factor of two is the margin asked for.
    EXPECT_LT(three, one / 2);
    EXPECT_LT(ten, three / 2);
    EXPECT_LT(ten, 0.001);
}

TEST(Iterations, NoneSetIsTheSolversOwnAndFewerThanOneRunsOne) {
    EXPECT_EQ(column_overlap(0), column_overlap(3));
    // A WorldDef built by hand may hold less: the stage still runs once rather than not at all.
    EXPECT_EQ(column_overlap(-2), column_overlap(1));
}

// The manifold solver takes the setting as the disc solver does: a stack of boxes settles
// differently at 2 iterations than at its own 6.
TEST(Iterations, ApplyToShapedBodiesToo) {
    const auto stack_top = [](int iterations) {
        WorldDef def;
        def.iterations = iterations;
        const testing::Material material{.restitution = 0.0, .friction = 0.5};
        def.walls.push_back(testing::box({-5, 0}, {5, 60}, material));
        for (int k = 0; k < 10; ++k) {
            def.bodies.push_back(testing::body(*box_shape(1, 1), {0, 0.501 + 1.001 * k}, 1, material));
        }
        World world(def);
        EXPECT_EQ(world.iterations(), iterations == 0 ? 6 : iterations);
        testing::run_for(world, 1.0);
        return world.bodies().back().position.y;
    };
    EXPECT_EQ(stack_top(0), stack_top(6));
    EXPECT_NE(stack_top(2), stack_top(6));
}

}  // namespace
}  // namespace discreel::physics

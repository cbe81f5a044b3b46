// WorldDef::iterations: how many sequential-impulse iterations the resting stage runs per
// substep. Gauss-Seidel on a stack converges slowly, so a tall column sinks into itself a
// little every substep and the projection pushes it back; more iterations leave it less to do.
#include <algorithm>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
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

TEST(Iterations, FewerThanOneRunsOne) {
    // A WorldDef built by hand may hold 0: the stage still runs once rather than not at all.
    EXPECT_EQ(column_overlap(0), column_overlap(1));
}

}  // namespace
}  // namespace discreel::physics

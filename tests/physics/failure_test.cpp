// A world whose state stops being finite says which disc and when, and stops stepping (the
// scene loader keeps scenes far from this; library users can still ask for anything).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::disc;

TEST(NonFiniteState, FoundInTheDefinition) {
    WorldDef def;
    def.bodies.push_back(disc({0, 0}, {0, 0}, 0.5, 1.0));
    def.bodies.push_back(disc({2, 0}, {std::numeric_limits<double>::quiet_NaN(), 0}, 0.5, 1.0));
    World world(def);
    ASSERT_TRUE(world.failure());
    EXPECT_EQ(world.failure()->body, 1u);
    EXPECT_EQ(world.failure()->t, 0.0);
    world.step();
    EXPECT_EQ(world.step_count(), 0) << "a failed world must not step";
}

// 8e307 m/s moves a disc 1.667e305 m per step at 480 Hz, so its x passes DBL_MAX
// (1.797e308) and becomes infinite in step 1079 (1078 * 1.667e305 = 1.7967e308 < DBL_MAX <
// 1079 * 1.667e305).
TEST(NonFiniteState, FoundAtTheStepThatOverflows) {
    WorldDef def;
    def.gravity = {0, 0};
    // Alone: near anything else, its squared speed (inf) would spoil the other's state first.
    def.bodies.push_back(disc({0, 10}, {8e307, 0}, 0.5, 1.0));
    World world(def);
    for (int k = 0; k < 2000 && !world.failure(); ++k) world.step();
    ASSERT_TRUE(world.failure());
    EXPECT_EQ(world.failure()->body, 0u);
    EXPECT_EQ(world.step_count(), 1079);
    EXPECT_DOUBLE_EQ(world.failure()->t, 1079.0 / 480.0);
    world.step();
    EXPECT_EQ(world.step_count(), 1079);
}

}  // namespace
}  // namespace discreel::physics

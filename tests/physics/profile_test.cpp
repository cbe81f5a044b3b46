// The stage profile (WorldDef::profile, World::profile): every stage of both solvers is timed,
// the stages and the rest add up to the steps' time, and timing changes no bit of the motion
// (the pinned hashes of busy_scene.hpp hold with it on).
#include <cstdint>
#include <functional>

#include <gtest/gtest.h>

#include "busy_scene.hpp"

namespace discreel::physics {
namespace {

struct Case {
    const char* name;
    std::function<WorldDef()> scene;
    std::uint64_t pinned_hash;
};

TEST(Profile, TimesEveryStageOfBothSolversAndChangesNoBit) {
    for (const Case& c : {Case{"discs", testing::busy_scene, testing::busy_scene_hash},
                          Case{"shapes", testing::mixed_scene, testing::mixed_scene_hash}}) {
        SCOPED_TRACE(c.name);
        WorldDef def = c.scene();
        def.profile = true;
        World world(def);
        testing::run_for(world, 2.0);
        EXPECT_EQ(testing::state_hash(world), c.pinned_hash);
        const StepProfile p = world.profile();
        // Both scenes have pairs, contacts, fast bodies and resting piles: every stage works.
        EXPECT_GT(p.pairs, 0.0);
        EXPECT_GT(p.contacts, 0.0);
        EXPECT_GT(p.impacts, 0.0);
        EXPECT_GT(p.velocities, 0.0);
        EXPECT_GT(p.positions, 0.0);
        // The rest is the steps' time less the stages' (throws, events, the step's own
        // bookkeeping): never below zero, the stages being timed inside the steps.
        EXPECT_GE(p.rest, -1e-9);
        EXPECT_GT(p.total(), p.velocities);
    }
}

TEST(Profile, IsZeroUnlessAsked) {
    World world(testing::mixed_scene());
    for (int k = 0; k < 100; ++k) world.step();
    const StepProfile p = world.profile();
    EXPECT_EQ(p.total(), 0.0);
    EXPECT_EQ(p.pairs, 0.0);
    EXPECT_EQ(p.rest, 0.0);
}

}  // namespace
}  // namespace discreel::physics

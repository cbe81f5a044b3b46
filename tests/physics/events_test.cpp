// Contact events: one per new contact, with the normal impulse of that step.
#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

TEST(Events, HeadOnCollisionGivesOneEventWithTheImpulse) {
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies = {testing::disc({0, 0}, {1, 0}, 0.25, 2.0), testing::disc({1, 0}, {0, 0}, 0.25, 2.0)};
    World world(def);
    testing::run_for(world, 1.0);
    const auto events = world.take_events();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].a, 0u);
    EXPECT_EQ(events[0].other_kind, ContactEvent::Other::body);
    EXPECT_EQ(events[0].other, 1u);
    EXPECT_NEAR(events[0].impulse, 2.0, 1e-12);  // m * dv = 2 kg * 1 m/s
    // Contact at t = 0.5 s: the event comes with the step that contains it.
    EXPECT_NEAR(events[0].t, 0.5, 1.0 / 480 + 1e-12);
    EXPECT_TRUE(world.take_events().empty());
}

TEST(Events, RestingDiscTouchesTheFloorOnce) {
    WorldDef def;
    def.walls.push_back(testing::box({0, 0}, {1, 1}, {.restitution = 0.0}));
    def.walls.push_back(testing::box({5, 5}, {6, 6}, {.restitution = 0.0}));
    def.bodies.push_back(testing::disc({0.5, 0.2}, {0, 0}, 0.1, 1.0, {.restitution = 0.0}));
    World world(def);
    testing::run_for(world, 1.0);
    const auto events = world.take_events();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].other_kind, ContactEvent::Other::wall);
    EXPECT_EQ(events[0].other, 0u);
    EXPECT_EQ(world.stats().contact_count, 1u);
}

}  // namespace
}  // namespace discreel::physics

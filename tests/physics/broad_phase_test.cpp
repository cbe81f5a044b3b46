// The broad phase numbers grid cells row by row when the discs' cells fit in its table, and
// hashes them when the discs are spread too far apart for that. Both must find exactly the same
// pairs, in the same order, so a crowd moves to the same bits whichever is used.
#include <cstddef>
#include <span>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

// A jostling crowd: 400 discs in a box, landing under gravity with random velocities.
WorldDef crowd() { return testing::pile({.count = 400, .spacing = 0.45, .speed = 3.0, .seed = 7}); }

TEST(BroadPhase, ADiscFarAwayChangesNothingInACrowd) {
    World nearby(crowd());
    WorldDef spread_def = crowd();
    // A peg a megametre away: the cells then span far more than the table holds, so they are
    // hashed. Static, so that it never moves the times at which the list is rebuilt (a disc
    // that uses up its margin would, and the list's pairs depend on when it was built).
    BodyDef peg = testing::disc({1.0e6, 0.0}, {0, 0}, 0.2, 0.1);
    peg.is_static = true;
    spread_def.bodies.push_back(peg);
    World spread(spread_def);
    testing::run_for(nearby, 1.5);
    testing::run_for(spread, 1.5);

    const std::span<const BodyState> a = nearby.bodies();
    const std::span<const BodyState> b = spread.bodies();
    ASSERT_EQ(a.size() + 1, b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        // Exact equality: any pair found by one path and not the other changes the crowd.
        ASSERT_EQ(a[i].position.x, b[i].position.x) << "disc " << i;
        ASSERT_EQ(a[i].position.y, b[i].position.y) << "disc " << i;
        ASSERT_EQ(a[i].velocity.x, b[i].velocity.x) << "disc " << i;
        ASSERT_EQ(a[i].velocity.y, b[i].velocity.y) << "disc " << i;
        ASSERT_EQ(a[i].angular_velocity, b[i].angular_velocity) << "disc " << i;
    }
    // And the crowd is really in contact: no pair was missed by both.
    EXPECT_GT(nearby.stats().contact_count, 300u);
    EXPECT_LT(nearby.stats().max_overlap_ratio, 0.01);
}

}  // namespace
}  // namespace discreel::physics

// The substep count a world runs: what WorldDef::substeps asks for, or for 0 the fewest that
// keep a substep at or under 1/480 s (docs/physics.md), whatever the step rate.
#include <gtest/gtest.h>

#include "discreel/physics.hpp"

namespace discreel::physics {
namespace {

int substeps_at(int rate, int asked) {
    WorldDef def;
    def.rate = rate;
    def.substeps = asked;
    return World(def).substeps();
}

TEST(Substeps, DefaultKeepsEachAtOrUnderA480thOfASecond) {
    EXPECT_EQ(substeps_at(480, 0), 1);
    EXPECT_EQ(substeps_at(960, 0), 1);
    EXPECT_EQ(substeps_at(240, 0), 2);
    EXPECT_EQ(substeps_at(60, 0), 8);
    EXPECT_EQ(substeps_at(50, 0), 10);  // 1/500 s: 9 would be 1/450 s, too long
    EXPECT_EQ(substeps_at(1, 0), 480);
    // The count is computed in floating point; no rate may round it up past the exact
    // ceil(480 / rate) (an extra substep at 480 Hz would double the cost of every scene).
    for (int rate = 1; rate <= 2000; ++rate) {
        ASSERT_EQ(substeps_at(rate, 0), (480 + rate - 1) / rate) << "rate " << rate;
    }
}

TEST(Substeps, AskedForIsKept) {
    EXPECT_EQ(substeps_at(240, 1), 1);
    EXPECT_EQ(substeps_at(480, 3), 3);
    EXPECT_EQ(substeps_at(60, 16), 16);
}

}  // namespace
}  // namespace discreel::physics

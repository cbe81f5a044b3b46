#include "timeline.hpp"

#include <gtest/gtest.h>

namespace discreel::job {
namespace {

TEST(TimelineTest, DivisibleRatesLandOnExactSteps) {
    const Timeline at60{.fps = 60, .rate = 480, .frame_count = 480};
    EXPECT_EQ(at60.step_for_frame(0), 0);
    EXPECT_EQ(at60.step_for_frame(1), 8);
    EXPECT_EQ(at60.step_for_frame(479), 479 * 8);
}

TEST(TimelineTest, SameTimeSameStepAtAnyFps) {
    const Timeline at30{.fps = 30, .rate = 480, .frame_count = 240};
    const Timeline at60{.fps = 60, .rate = 480, .frame_count = 480};
    for (int frame = 0; frame < 240; ++frame) {
        EXPECT_EQ(at30.step_for_frame(frame), at60.step_for_frame(2 * frame)) << frame;
    }
}

TEST(TimelineTest, NonDivisibleRatesRoundToNearestStep) {
    const Timeline t{.fps = 7, .rate = 480, .frame_count = 70};
    EXPECT_EQ(t.step_for_frame(1), 69);    // 68.57 -> 69
    EXPECT_EQ(t.step_for_frame(2), 137);   // 137.14 -> 137
    EXPECT_EQ(t.step_for_frame(7), 480);   // exactly one second
}

TEST(TimelineTest, LongClipsDoNotOverflow) {
    const Timeline t{.fps = 240, .rate = 100000, .frame_count = 240 * 3600};
    // 863999 * 100000 / 240 = 359999583.3: needs 64-bit intermediates.
    EXPECT_EQ(t.step_for_frame(240 * 3600 - 1), 359999583);
}

}  // namespace
}  // namespace discreel::job

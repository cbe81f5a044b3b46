// The progress line's text and when it is printed, with elapsed times given explicitly.
#include <gtest/gtest.h>

#include <sstream>

#include "progress.hpp"

namespace discreel::app {
namespace {

TEST(ProgressTest, LineShowsFramesRateElapsedAndTimeLeft) {
    // 300 of 600 frames in 5 s: 60 fps, so the other 300 take 5 s more.
    EXPECT_EQ(format_progress(300, 600, 5.0),
              "frame 300/600 (50%), 60.0 fps, elapsed 0:05, left 0:05");
    // 100 of 36 000 in 50 s: 2 fps, 35 900 frames left = 17 950 s = 4:59:10.
    EXPECT_EQ(format_progress(100, 36000, 50.0),
              "frame 100/36000 (0%), 2.0 fps, elapsed 0:50, left 4:59:10");
    EXPECT_EQ(format_progress(0, 600, 0.0), "frame 0/600 (0%), 0.0 fps, elapsed 0:00, left ?");
}

TEST(ProgressTest, StyleFollowsTheTerminalUnlessForcedOrQuiet) {
    using enum ProgressRequest;
    EXPECT_EQ(pick_progress_style(false, none, true), ProgressStyle::terminal);
    EXPECT_EQ(pick_progress_style(false, none, false), ProgressStyle::none);
    EXPECT_EQ(pick_progress_style(false, lines, false), ProgressStyle::lines);
    EXPECT_EQ(pick_progress_style(true, none, true), ProgressStyle::none);
    // JSON is for programs: the same on a terminal, and off only with --quiet.
    EXPECT_EQ(pick_progress_style(false, json, true), ProgressStyle::json);
    EXPECT_EQ(pick_progress_style(false, json, false), ProgressStyle::json);
    EXPECT_EQ(pick_progress_style(true, json, false), ProgressStyle::none);
}

TEST(ProgressTest, JsonHasOneObjectPerUpdateAndAFinalDoneObject) {
    std::ostringstream out;
    ProgressMeter meter(out, ProgressStyle::json, 10);
    meter.update(0, 0.0);   // nothing done yet: no rate, so no estimate
    meter.update(5, 1.0);   // due: one second after the first
    meter.update(6, 1.5);   // within the second: skipped
    meter.update(10, 1.6);
    meter.finish();
    meter.done(1.75);
    EXPECT_EQ(out.str(),
              "{\"stage\":\"render\",\"frame\":0,\"frames\":10,\"fps\":0.00,\"elapsed\":0.000,"
              "\"eta\":null}\n"
              "{\"stage\":\"render\",\"frame\":5,\"frames\":10,\"fps\":5.00,\"elapsed\":1.000,"
              "\"eta\":1.000}\n"
              "{\"stage\":\"render\",\"frame\":10,\"frames\":10,\"fps\":6.25,\"elapsed\":1.600,"
              "\"eta\":0.000}\n"
              "{\"stage\":\"done\",\"frame\":10,\"frames\":10,\"fps\":5.71,\"elapsed\":1.750,"
              "\"eta\":0.000}\n");
}

TEST(ProgressTest, LinesComeOncePerSecondAndForTheLastFrame) {
    std::ostringstream out;
    ProgressMeter meter(out, ProgressStyle::lines, 10);
    meter.update(1, 0.1);   // the first update is due at once
    meter.update(2, 0.5);   // within the second: skipped
    meter.update(3, 1.2);
    meter.update(10, 1.3);  // the last frame is always shown
    meter.finish();
    EXPECT_EQ(out.str(),
              "frame 1/10 (10%), 10.0 fps, elapsed 0:00, left 0:01\n"
              "frame 3/10 (30%), 2.5 fps, elapsed 0:01, left 0:03\n"
              "frame 10/10 (100%), 7.7 fps, elapsed 0:01, left 0:00\n");
}

TEST(ProgressTest, TerminalRedrawsOneLineAndErasesItAtTheEnd) {
    std::ostringstream out;
    ProgressMeter meter(out, ProgressStyle::terminal, 4);
    meter.update(2, 1.0);
    meter.update(4, 2.0);
    meter.finish();
    EXPECT_EQ(out.str(),
              "\rframe 2/4 (50%), 2.0 fps, elapsed 0:01, left 0:01\x1b[K"
              "\rframe 4/4 (100%), 2.0 fps, elapsed 0:02, left 0:00\x1b[K"
              "\r\x1b[K");
}

TEST(ProgressTest, NoneStaysSilent) {
    std::ostringstream out;
    ProgressMeter meter(out, ProgressStyle::none, 4);
    meter.update(4, 1.0);
    meter.finish();
    EXPECT_EQ(out.str(), "");
}

}  // namespace
}  // namespace discreel::app

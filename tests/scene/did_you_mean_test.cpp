// Edit distance and the plausibility rule behind "did you mean".
#include <array>
#include <string_view>

#include <gtest/gtest.h>

#include "discreel/did_you_mean.hpp"

namespace discreel::scene::detail {
namespace {

constexpr std::array<std::string_view, 4> video_keys{"size", "fps", "duration", "background"};

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
    EXPECT_EQ(edit_distance("color", "color"), 0u);
    EXPECT_EQ(edit_distance("colour", "color"), 1u);   // deletion
    EXPECT_EQ(edit_distance("sise", "size"), 1u);      // substitution
    EXPECT_EQ(edit_distance("raduis", "radius"), 1u);  // adjacent swap
    EXPECT_EQ(edit_distance("Radius", "radius"), 0u);  // case is not a difference
    EXPECT_EQ(edit_distance("", "abc"), 3u);
    EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(ClosestMatch, SuggestsOnlyPlausibleTypos) {
    EXPECT_EQ(closest_match("sise", video_keys), "size");
    EXPECT_EQ(closest_match("durration", video_keys), "duration");
    EXPECT_EQ(closest_match("FPS", video_keys), "fps");
    EXPECT_EQ(closest_match("frames_per_second", video_keys), std::nullopt);
    EXPECT_EQ(closest_match("fp", video_keys), "fps");
    EXPECT_EQ(closest_match("x", video_keys), std::nullopt);  // two edits from "fps" is a guess
}

TEST(ClosestMatch, TiesGoToTheEarliestCandidate) {
    constexpr std::array<std::string_view, 2> keys{"cat", "cut"};
    EXPECT_EQ(closest_match("cot", keys), "cat");
}

}  // namespace
}  // namespace discreel::scene::detail

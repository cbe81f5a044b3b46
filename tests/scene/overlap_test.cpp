// The overlap grid behind the t = 0 check and random placement.
#include <gtest/gtest.h>

#include "overlap.hpp"

namespace discreel::scene::detail {
namespace {

TEST(Overlap, TouchingIsNotOverlappingButAnyDeeperContactIs) {
    EXPECT_FALSE(overlapping({{0, 0}, 0.5}, {{1, 0}, 0.5}));
    // 0.1 + 0.2 != 0.3 in binary: a grid of touching discs must not be flagged for it.
    EXPECT_FALSE(overlapping({{0, 0}, 0.15}, {{0.1 + 0.2, 0}, 0.15}));
    EXPECT_TRUE(overlapping({{0, 0}, 0.5}, {{1 - 1e-6, 0}, 0.5}));
}

TEST(Overlap, TwoStaticDiscsMayOverlapOnPurpose) {
    EXPECT_FALSE(overlapping({{0, 0}, 0.5, true}, {{0.1, 0}, 0.5, true}));
    EXPECT_TRUE(overlapping({{0, 0}, 0.5, true}, {{0.1, 0}, 0.5, false}));
}

TEST(Overlap, ReportsEachLaterCircleWithItsEarliestPartner) {
    const std::vector<Circle> circles{
        {{0, 0}, 1}, {{5, 5}, 1}, {{1.5, 0}, 1}, {{5, 6}, 1}, {{20, 20}, 1}, {{0.5, 0}, 1}};
    const std::vector<bool> all(circles.size(), true);
    const auto found = find_overlaps(circles, all);
    const std::vector<std::pair<std::size_t, std::size_t>> expected{{2, 0}, {3, 1}, {5, 0}};
    EXPECT_EQ(found, expected);
}

TEST(Overlap, LeftOutCirclesTakeNoPart) {
    const std::vector<Circle> circles{{{0, 0}, 1}, {{0.5, 0}, 1}};
    EXPECT_TRUE(find_overlaps(circles, {true, false}).empty());
}

TEST(Overlap, CirclesInFarApartCellsAreStillFound) {
    // A large circle next to small ones: the cell size follows the largest, so the small
    // circle just across a cell boundary is still compared.
    const std::vector<Circle> circles{{{0, 0}, 3}, {{3.05, 0}, 0.1}, {{100, 0}, 0.1}};
    const auto found = find_overlaps(circles, {true, true, true});
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0], (std::pair<std::size_t, std::size_t>{1, 0}));
}

}  // namespace
}  // namespace discreel::scene::detail

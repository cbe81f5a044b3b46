// Which discs the renderer may draw as point sprites (no GL needed).
#include <gtest/gtest.h>

#include <limits>

#include "instances.hpp"

namespace discreel::render {
namespace {

DiscInstance at(float x, float y, float radius) {
    return {.center = {x, y}, .radius = radius, .angle = 0, .color = {1, 1, 1, 1}, .flags = 0};
}

// A 200x100 frame: centres within 99 x 49 pixels of the middle keep a pixel to the edge.
constexpr int kWidth = 200;
constexpr int kHeight = 100;
constexpr float kMaxPointSize = 64;

TEST(PointSpriteTest, ADiscWhoseCentreIsInsideTheFrameFits) {
    EXPECT_TRUE(fits_point_sprite(at(0, 0, 5), kWidth, kHeight, kMaxPointSize));
    EXPECT_TRUE(fits_point_sprite(at(-99, 49, 5), kWidth, kHeight, kMaxPointSize));
}

TEST(PointSpriteTest, ADiscWhoseCentreIsOutsideOrOnTheEdgeDoesNot) {
    EXPECT_FALSE(fits_point_sprite(at(99.5f, 0, 5), kWidth, kHeight, kMaxPointSize));
    EXPECT_FALSE(fits_point_sprite(at(0, -49.5f, 5), kWidth, kHeight, kMaxPointSize));
    EXPECT_FALSE(fits_point_sprite(at(150, 0, 5), kWidth, kHeight, kMaxPointSize));
}

TEST(PointSpriteTest, TheSpriteIsTheDiscPlusAPixelOfMarginEachSide) {
    // 2 (31 + 1) = 64 fits; a little more does not.
    EXPECT_TRUE(fits_point_sprite(at(0, 0, 31), kWidth, kHeight, kMaxPointSize));
    EXPECT_FALSE(fits_point_sprite(at(0, 0, 31.01f), kWidth, kHeight, kMaxPointSize));
    // Sub-pixel discs are drawn half a pixel in radius: 2 (0.5 + 1) = 3.
    EXPECT_TRUE(fits_point_sprite(at(0, 0, 0.01f), kWidth, kHeight, 3));
    EXPECT_FALSE(fits_point_sprite(at(0, 0, 0.01f), kWidth, kHeight, 2.9f));
}

TEST(PointSpriteTest, ANonFiniteCentreIsLeftToTheQuadPath) {
    EXPECT_FALSE(fits_point_sprite(at(std::numeric_limits<float>::quiet_NaN(), 0, 5), kWidth,
                                   kHeight, kMaxPointSize));
}

}  // namespace
}  // namespace discreel::render

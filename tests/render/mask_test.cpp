// Instance masks (CPU, no GL): which geometry is on top at each pixel centre, with the
// renderer's camera mapping and drawing order.
#include <gtest/gtest.h>

#include "discreel/render.hpp"

namespace discreel::render {
namespace {

// A 10 x 10 m view on 100 x 100 pixels: 10 pixels a metre, the world's origin at the centre.
FrameScene ten_metres() {
    FrameScene frame;
    frame.camera = {.center_x = 0, .center_y = 0, .height = 10};
    return frame;
}

std::uint16_t at(const std::vector<std::uint16_t>& ids, int i, int j) {
    return ids[static_cast<std::size_t>(j) * 100 + static_cast<std::size_t>(i)];
}

TEST(MaskTest, ThePixelTransformPutsWorldPointsWhereTheRendererDraws) {
    const PixelTransform m = pixel_transform({.center_x = 1, .center_y = 2, .height = 10}, 200, 100);
    EXPECT_DOUBLE_EQ(m.pixels_per_metre, 10);
    // The camera's centre is the image's centre; y points down in pixels.
    EXPECT_DOUBLE_EQ(m.m00 * 1 + m.m01 * 2 + m.m02, 100);
    EXPECT_DOUBLE_EQ(m.m10 * 1 + m.m11 * 2 + m.m12, 50);
    EXPECT_DOUBLE_EQ(m.m10 * 1 + m.m11 * 3 + m.m12, 40);   // a metre up is 10 pixels up
}

TEST(MaskTest, ShapesCoverThePixelsWhoseCentresTheyHoldLaterOnTop) {
    FrameScene frame = ten_metres();
    frame.capsules.push_back({.ax = -5, .ay = -4, .bx = 5, .by = -4, .radius = 0.2, .color = {}});
    PolygonGeom square;
    square.x = 2;
    square.y = 0;
    square.vertices = {-1, -1, 1, -1, 1, 1, -1, 1};
    square.count = 4;
    square.fill.a = 1;
    square.mask_id = 7;
    frame.polygons.push_back(square);
    DiscGeom disc;
    disc.x = 1;
    disc.y = 0;
    disc.radius = 1;
    disc.fill.a = 1;
    disc.mask_id = 3;
    frame.discs.push_back(disc);
    DiscGeom hidden = disc;   // transparent: it hides nothing
    hidden.x = -3;
    hidden.fill.a = 0;
    hidden.mask_id = 9;
    frame.discs.push_back(hidden);

    const auto ids = draw_mask(frame, 100, 100);
    ASSERT_EQ(ids.size(), 10000u);
    // The wall at y = -4, 0.2 m (2 pixels) each side: the rows whose centres are within,
    // 88..91 (y = -3.85 .. -4.15).
    EXPECT_EQ(at(ids, 50, 88), wall_mask_id);
    EXPECT_EQ(at(ids, 50, 91), wall_mask_id);
    EXPECT_EQ(at(ids, 50, 87), 0);
    EXPECT_EQ(at(ids, 50, 92), 0);
    EXPECT_EQ(at(ids, 60, 50), 3);               // the disc, drawn after the square, on top
    EXPECT_EQ(at(ids, 75, 50), 7);               // the square beyond the disc
    EXPECT_EQ(at(ids, 79, 59), 7);               // its corner pixel (centre at 2.95, -0.95)
    EXPECT_EQ(at(ids, 80, 50), 0);
    EXPECT_EQ(at(ids, 20, 50), 0);               // the transparent disc
    EXPECT_EQ(std::count(ids.begin(), ids.end(), 9), 0);
    // The disc's pixels are those whose centres are within 1 m of (1, 0), less none on top.
    int disc_pixels = 0;
    for (int j = 0; j < 100; ++j) {
        for (int i = 0; i < 100; ++i) {
            const double x = (i + 0.5 - 50) / 10, y = (50 - j - 0.5) / 10;
            disc_pixels += (x - 1) * (x - 1) + y * y <= 1;
        }
    }
    EXPECT_EQ(std::count(ids.begin(), ids.end(), 3), disc_pixels);
}

TEST(MaskTest, AShapeThinnerThanAPixelStillHoldsItsPixel) {
    FrameScene frame = ten_metres();
    DiscGeom speck;
    speck.x = 0.05;   // the centre of pixel (50, 49)
    speck.y = 0.05;
    speck.radius = 0.001;
    speck.fill.a = 1;
    speck.mask_id = 1;
    frame.discs.push_back(speck);
    const auto ids = draw_mask(frame, 100, 100);
    EXPECT_EQ(at(ids, 50, 49), 1);
    EXPECT_EQ(std::count(ids.begin(), ids.end(), 1), 1);
}

}  // namespace
}  // namespace discreel::render

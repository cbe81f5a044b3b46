// Golden-image test: a small frame with every kind of geometry, compared with a committed PNG
// (see golden_check.hpp for the tolerance and for regenerating).
#include <gtest/gtest.h>

#include "discreel/render.hpp"
#include "golden_check.hpp"

namespace discreel::render {
namespace {

using test::check_golden;

// 320x180, 20 pixels per metre: a box of capsule walls, a slanted wall, moving discs of
// several sizes, colours and angles (one translucent, two near the one-pixel floor), and pegs.
FrameScene golden_scene() {
    FrameScene f;
    f.background = {0.11f, 0.12f, 0.15f, 1};
    f.camera = {.center_x = 0, .center_y = 0, .height = 9};
    const Rgba wall{0.55f, 0.58f, 0.64f, 1};
    const float w = 7.8f, h = 4.3f, t = 0.1f;
    f.capsules = {
        {.ax = -w, .ay = -h, .bx = w, .by = -h, .radius = t, .color = wall},
        {.ax = -w, .ay = h, .bx = w, .by = h, .radius = t, .color = wall},
        {.ax = -w, .ay = -h, .bx = -w, .by = h, .radius = t, .color = wall},
        {.ax = w, .ay = -h, .bx = w, .by = h, .radius = t, .color = wall},
        {.ax = -5, .ay = 1.5f, .bx = -2, .by = 0.5f, .radius = 0.2f, .color = {0.8f, 0.6f, 0.3f, 1}},
    };
    auto moving = [](float x, float y, float r, float angle, Rgba fill) {
        return DiscGeom{.x = x, .y = y, .radius = r, .angle = angle, .fill = fill};
    };
    auto peg = [](float x, float y, float r, Rgba fill) {
        return DiscGeom{.x = x, .y = y, .radius = r, .fill = fill, .is_static = true};
    };
    f.discs = {
        moving(-5, -2, 1.6f, 0.5f, {0.90f, 0.30f, 0.25f, 1}),
        moving(-1.5f, -2.5f, 1.1f, 2.0f, {0.25f, 0.60f, 0.95f, 1}),
        moving(1.8f, 2, 1.3f, -1.0f, {0.95f, 0.85f, 0.30f, 1}),
        moving(4.8f, -1.5f, 0.7f, 3.5f, {0.35f, 0.80f, 0.45f, 1}),
        moving(3.2f, 0.8f, 0.4f, 0.0f, {0.80f, 0.40f, 0.85f, 1}),
        moving(6.0f, 2.8f, 0.1f, 0.0f, {0.95f, 0.95f, 0.95f, 1}),
        moving(6.6f, 2.8f, 0.02f, 0.0f, {0.95f, 0.95f, 0.95f, 1}),
        peg(-1, 1.8f, 0.5f, {0.60f, 0.62f, 0.68f, 1}),
        peg(0.0f, 0.6f, 0.7f, {0.85f, 0.50f, 0.20f, 1}),
        moving(-0.8f, -1.8f, 0.8f, 1.0f, {0.95f, 0.95f, 0.95f, 0.6f}),
    };
    return f;
}

TEST(RenderGoldenGLTest, MixedScene) {
    check_golden("mixed_scene", golden_scene(), 320, 180);
}

}  // namespace
}  // namespace discreel::render

// The style switches and overlays: a golden image per feature (golden_check.hpp states the
// tolerance), and exact checks of what each feature must do to particular pixels.
#include <gtest/gtest.h>

#include <cmath>

#include "discreel/render.hpp"
#include "golden_check.hpp"
#include "render_test_support.hpp"

namespace discreel::render {
namespace {

using test::check_golden;
using test::opaque;
using test::Pixel;
using test::pixel_at;
using test::pixel_at_world;

constexpr int kWidth = 320, kHeight = 180;
const Rgba kBackground{0.11f, 0.12f, 0.15f, 1};
const Rgba kRed{0.90f, 0.30f, 0.25f, 1};
const Rgba kBlue{0.25f, 0.60f, 0.95f, 1};
const Rgba kYellow{0.95f, 0.85f, 0.30f, 1};

// 320x180 at 20 pixels per metre: a floor, three moving discs at different angles and a peg,
// large enough that outline and spoke are clearly visible.
FrameScene style_scene() {
    FrameScene f;
    f.background = kBackground;
    f.camera = {.center_x = 0, .center_y = 0, .height = 9};
    f.capsules = {{.ax = -7.5f, .ay = -4, .bx = 7.5f, .by = -4, .radius = 0.12f,
                   .color = {0.55f, 0.58f, 0.64f, 1}}};
    f.discs = {
        {.x = -4.5f, .y = -1, .radius = 1.6f, .angle = 0.6f, .fill = kRed},
        {.x = 0, .y = 1, .radius = 1.2f, .angle = 2.4f, .fill = kBlue},
        {.x = 4.2f, .y = -1.5f, .radius = 1.0f, .angle = -1.2f, .fill = kYellow},
        {.x = 4.5f, .y = 2.4f, .radius = 0.7f, .fill = {0.60f, 0.62f, 0.68f, 1}, .is_static = true},
    };
    return f;
}

Image draw(const FrameScene& frame) {
    auto renderer = Renderer::create({.width = kWidth, .height = kHeight});
    EXPECT_TRUE(renderer.ok()) << renderer.error().message;
    auto image = renderer->draw(frame);
    EXPECT_TRUE(image.ok()) << image.error().message;
    return {image->width, image->height,
            std::vector<std::uint8_t>(image->rgba.begin(), image->rgba.end())};
}

bool is_background(const Pixel& p) { return p == opaque(kBackground); }

// --- Goldens, one per feature ---------------------------------------------------------------

TEST(StyleGoldenGLTest, OutlineWithoutSpinMarker) {
    FrameScene f = style_scene();
    f.spin_markers = false;
    check_golden("style_outline", f, kWidth, kHeight);
}

TEST(StyleGoldenGLTest, SpinMarkerWithoutOutline) {
    FrameScene f = style_scene();
    f.disc_outlines = false;
    check_golden("style_spin_marker", f, kWidth, kHeight);
}

TEST(StyleGoldenGLTest, VelocityArrows) {
    FrameScene f = style_scene();
    const Rgba white{1, 1, 1, 1};
    const auto arrow = [](float x0, float y0, float x1, float y1, float width, Rgba color) {
        return ArrowGeom{.tail_x = x0, .tail_y = y0, .head_x = x1, .head_y = y1, .width = width,
                         .color = color};
    };
    f.arrows = {arrow(-4.5f, -1, -1.5f, 1.5f, 2, white), arrow(0, 1, 0, 3.8f, 2, white),
                arrow(4.2f, -1.5f, 1.8f, -3, 3, kYellow)};
    check_golden("style_velocity_arrows", f, kWidth, kHeight);
}

TEST(StyleGoldenGLTest, Trails) {
    FrameScene f = style_scene();
    // A fading, thinning arc behind the blue disc, as the frame-scene builder makes them:
    // colours premixed toward the background, oldest first.
    const int segments = 12;
    for (int k = segments; k-- > 0;) {
        const float fresh = 1.0f - (static_cast<float>(k) + 0.5f) / segments;
        const auto at = [](int i) { return std::array<float, 2>{-0.5f * i, 1 - 0.04f * i * i}; };
        const auto a = at(k + 1), b = at(k);
        const float m = 0.65f * fresh;
        f.trails.push_back({a[0], a[1], b[0], b[1], 0.48f * (0.3f + 0.7f * fresh),
                            {kBackground.r + (kBlue.r - kBackground.r) * m,
                             kBackground.g + (kBlue.g - kBackground.g) * m,
                             kBackground.b + (kBlue.b - kBackground.b) * m, 1}});
    }
    check_golden("style_trails", f, kWidth, kHeight);
}

TEST(StyleGoldenGLTest, ClockText) {
    FrameScene f = style_scene();
    f.texts = {{.text = "t = 12.50 s  frame 750", .corner = Corner::top_left, .dot = 2,
                .color = {1, 1, 1, 1}},
               {.text = "0123456789 :=-/ safe?", .corner = Corner::bottom_right, .dot = 1,
                .color = kYellow}};
    // Glyphs are whole-pixel squares with no anti-aliasing: no pixel may differ (beyond the
    // channel tolerance), so a single wrong dot fails.
    check_golden("style_clock", f, kWidth, kHeight, 0);
}

// --- Exact checks ---------------------------------------------------------------------------

TEST(StyleGLTest, OutlineSwitchDarkensTheRimOnly) {
    FrameScene f = style_scene();
    f.discs.resize(1);
    f.spin_markers = false;
    const Image with = draw(f);
    f.disc_outlines = false;
    const Image without = draw(f);
    // Just inside the red disc's edge (1.6 m = 32 px; the rim is ~2.5 px wide), on its left.
    const Pixel rim_with = pixel_at_world(with.view(), f.camera, -4.5 - 1.55, -1);
    const Pixel rim_without = pixel_at_world(without.view(), f.camera, -4.5 - 1.55, -1);
    const Pixel centre = pixel_at_world(without.view(), f.camera, -4.5, -1);
    EXPECT_EQ(rim_without, centre);
    EXPECT_LT(rim_with[0], rim_without[0] - 40);
    EXPECT_EQ(pixel_at_world(with.view(), f.camera, -4.5, -1),
              pixel_at_world(without.view(), f.camera, -4.5, -1));
}

TEST(StyleGLTest, SpinMarkerPointsAlongTheAngleAndCanBeSwitchedOff) {
    FrameScene f = style_scene();
    f.discs = {{.x = 0, .y = 0, .radius = 2, .angle = 0.5f * 3.14159265f, .fill = kBlue}};
    f.disc_outlines = false;
    const Image on = draw(f);
    // The spoke runs from the centre toward +y (angle pi/2): light over the blue fill.
    EXPECT_NE(pixel_at_world(on.view(), f.camera, 0, 1.2), opaque(kBlue));
    EXPECT_EQ(pixel_at_world(on.view(), f.camera, 0, -1.2), opaque(kBlue));
    EXPECT_EQ(pixel_at_world(on.view(), f.camera, 1.2, 0), opaque(kBlue));
    f.spin_markers = false;
    const Image off = draw(f);
    EXPECT_EQ(pixel_at_world(off.view(), f.camera, 0, 1.2), opaque(kBlue));
}

TEST(StyleGLTest, ArrowPointsFromTailToHead) {
    FrameScene f;
    f.background = kBackground;
    f.camera = {.center_x = 0, .center_y = 0, .height = 9};   // 20 px per metre
    const Rgba white{1, 1, 1, 1};
    f.arrows = {{.tail_x = -3, .tail_y = 0, .head_x = 3, .head_y = 0, .width = 2, .color = white}};
    const Image image = draw(f);
    const ImageView v = image.view();
    // Shaft along y = 0 (pixel rows 89 and 90 both touch it), nothing beyond the head.
    EXPECT_EQ(pixel_at_world(v, f.camera, 0, 0.02), opaque(white));
    EXPECT_TRUE(is_background(pixel_at_world(v, f.camera, 3.5, 0.02)));
    EXPECT_TRUE(is_background(pixel_at_world(v, f.camera, -3.5, 0.02)));
    // The barbs (10 px long at width 2) lean back toward the tail, above and below the shaft.
    const double back = 0.4, side = 0.22;   // metres from the head, along the barbs
    EXPECT_FALSE(is_background(pixel_at_world(v, f.camera, 3 - back, side)));
    EXPECT_FALSE(is_background(pixel_at_world(v, f.camera, 3 - back, -side)));
    EXPECT_TRUE(is_background(pixel_at_world(v, f.camera, 3 + back, side)));
    EXPECT_TRUE(is_background(pixel_at_world(v, f.camera, -3 + back, side)));
}

TEST(StyleGLTest, ArrowsShorterThanAPixelAreNotDrawn) {
    FrameScene f;
    f.background = kBackground;
    f.camera = {.center_x = 0, .center_y = 0, .height = 9};
    f.arrows = {{.tail_x = 0, .tail_y = 0, .head_x = 0.01f, .head_y = 0, .width = 4,
                 .color = {1, 1, 1, 1}}};
    const Image image = draw(f);
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        ASSERT_EQ(image.rgba[i], opaque(kBackground)[0]) << "pixel " << i / 4;
}

TEST(StyleGLTest, TextLandsInItsCorner) {
    for (const Corner corner :
         {Corner::top_left, Corner::top_right, Corner::bottom_left, Corner::bottom_right}) {
        FrameScene f;
        f.background = kBackground;
        f.camera = {.center_x = 0, .center_y = 0, .height = 9};
        f.texts = {{.text = "t = 1.25 s", .corner = corner, .dot = 2, .color = {1, 1, 1, 1}}};
        const Image image = draw(f);
        int lit[2][2] = {};   // [bottom][right]: pixels that are not background, per quadrant
        int white = 0;
        for (int row = 0; row < kHeight; ++row)
            for (int column = 0; column < kWidth; ++column) {
                const Pixel p = pixel_at(image.view(), column, row);
                if (is_background(p)) continue;
                ++lit[row >= kHeight / 2][column >= kWidth / 2];
                white += p == Pixel{255, 255, 255, 255};
            }
        const bool bottom = corner == Corner::bottom_left || corner == Corner::bottom_right;
        const bool right = corner == Corner::top_right || corner == Corner::bottom_right;
        SCOPED_TRACE(static_cast<int>(corner));
        // Ten glyphs of 2x2-pixel dots (8 glyphs with dots, at least 6 dots each) plus shadow.
        EXPECT_GT(lit[bottom][right], 8 * 6 * 4);
        EXPECT_EQ(lit[!bottom][right] + lit[bottom][!right] + lit[!bottom][!right], 0);
        // Dots are whole pixels: the text colour appears exactly, unblended.
        EXPECT_GT(white, 8 * 6 * 4 / 2);
    }
}

TEST(StyleGLTest, GlyphDotsFollowTheFontPattern) {
    FrameScene f;
    f.background = kBackground;
    const int dot = 3;
    f.texts = {{.text = "1t", .corner = Corner::top_left, .dot = dot, .color = {1, 1, 1, 1}}};
    const Image image = draw(f);
    // '1' and 't' as drawn in glyph_font.cpp; the text's top-left corner is 4 dots in from
    // the frame's top-left corner, glyphs 6 dots apart. Every row matters (the last ones
    // once fell outside a 32-bit pattern).
    const char* rows[7] = {"  #     #  ", " ##     #  ", "  #   #####", "  #     #  ",
                           "  #     #  ", "  #     #  ", " ###     ##"};
    for (int row = 0; row < 7; ++row)
        for (int column = 0; column < 11; ++column) {
            const Pixel p = pixel_at(image.view(), (4 + column) * dot + dot / 2,
                                     (4 + row) * dot + dot / 2);
            EXPECT_EQ(p == (Pixel{255, 255, 255, 255}), rows[row][column] == '#')
                << "dot row " << row << ", column " << column;
        }
}

TEST(StyleGLTest, UnknownCharactersShowAsQuestionMarks) {
    FrameScene f;
    f.background = kBackground;
    const auto text_frame = [&](std::string text) {
        f.texts = {{.text = std::move(text), .corner = Corner::top_left, .dot = 1,
                    .color = {1, 1, 1, 1}}};
        return draw(f);
    };
    const Image unknown = text_frame("Q");
    const Image question = text_frame("?");
    EXPECT_EQ(unknown.rgba, question.rgba);
}

}  // namespace
}  // namespace discreel::render

namespace discreel::render {
namespace {

// Text: a label's glyphs land where its anchor puts them, in its colour over the frame; a
// frame without text never needs the font, and one with text names the font it could not read.
TEST(TextGLTest, ALabelIsDrawnAtItsAnchorAndAMissingFontIsNamed) {
    FrameScene f;
    f.background = {0, 0, 0, 1};
    f.camera = {.center_x = 0, .center_y = 0, .height = 9};
    f.labels.push_back({.text = "MMMM", .world = false, .x = 0.25, .y = 0.5, .size = 0.2,
                        .anchor = Anchor::left, .color = {1, 1, 1, 1}, .outline = {}});
    const Image image = draw(f);
    int left_half = 0, right_half = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * kWidth + x) * 4];
            if (p[0] < 128) continue;
            EXPECT_GE(x, kWidth / 4 - 2) << "text left of its anchor at " << x << ", " << y;
            (x < kWidth / 2 ? left_half : right_half) += 1;
        }
    }
    EXPECT_GT(left_half, 100);   // four 36-pixel Ms start at the anchor
    EXPECT_GT(right_half, 100);  // and reach past the middle

    auto renderer = Renderer::create({.width = kWidth, .height = kHeight, .font = "/no/such.ttf"});
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    FrameScene plain = f;
    plain.labels.clear();
    EXPECT_TRUE(renderer->draw(plain).ok());
    const auto failed = renderer->draw(f);
    ASSERT_FALSE(failed.ok());
    EXPECT_EQ(failed.error().message, "text needs the font /no/such.ttf, which could not be read "
                                      "(Debian package fonts-dejavu-core)");
}

}  // namespace
}  // namespace discreel::render

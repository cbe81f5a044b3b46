// Pixel-exact properties of the renderer that need no golden image: camera placement, y up,
// colours, draw order, opacity, determinism and error messages.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "discreel/render.hpp"
#include "render_test_support.hpp"

namespace discreel::render {
namespace {

using test::opaque;
using test::Pixel;
using test::pixel_at;
using test::pixel_at_world;
using ::testing::HasSubstr;

// Channel values that are whole bytes, so the expected framebuffer contents are exact.
constexpr Rgba kBackground{20 / 255.0f, 24 / 255.0f, 40 / 255.0f, 1};
constexpr Rgba kRed{200 / 255.0f, 60 / 255.0f, 40 / 255.0f, 1};
constexpr Rgba kBlue{40 / 255.0f, 90 / 255.0f, 220 / 255.0f, 1};
constexpr Rgba kWall{150 / 255.0f, 150 / 255.0f, 160 / 255.0f, 1};

// 160x90 pixels showing 9 m vertically: 10 pixels per metre, 16 m x 9 m visible.
constexpr int kWidth = 160;
constexpr int kHeight = 90;
constexpr Camera kCamera{.center_x = 0, .center_y = 0, .height = 9};

FrameScene empty_frame() {
    FrameScene frame;
    frame.background = kBackground;
    frame.camera = kCamera;
    return frame;
}

DiscGeom disc(float x, float y, float radius, float angle, Rgba fill, bool is_static = false) {
    return {.x = x, .y = y, .radius = radius, .angle = angle, .fill = fill, .is_static = is_static};
}

// Interior pixels away from outline and marker are the fill colour itself; the shader blends
// with weight exactly 0 there, so only float-to-byte rounding (one unit) may differ.
void expect_near_color(const Pixel& actual, const Pixel& expected) {
    for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(actual[c], expected[c], 1) << "channel " << c;
    }
}

int channel_sum(const Pixel& p) { return p[0] + p[1] + p[2]; }

class RendererGLTest : public ::testing::Test {
protected:
    void SetUp() override {
        auto created = Renderer::create({.width = kWidth, .height = kHeight});
        ASSERT_TRUE(created.ok()) << created.error().message;
        renderer_.emplace(std::move(created.value()));
    }

    // A copy, so that several frames can be compared after further draws.
    Image draw(const FrameScene& frame) {
        auto view = renderer_->draw(frame);
        EXPECT_TRUE(view.ok()) << (view.ok() ? "" : view.error().message);
        if (!view.ok()) return {};
        return {view->width, view->height, {view->rgba.begin(), view->rgba.end()}};
    }

    // `cut` has something whose centre lies beyond the right edge (drawn as a quad); with the
    // camera 1 m (10 pixels) further right its centre is inside (a point sprite). The right
    // 20 columns must look the same, but for the two primitives interpolating local coordinates
    // differently, which moves a colour by at most one unit after rounding.
    void expect_same_further_in(const FrameScene& cut) {
        FrameScene inside = cut;
        inside.camera.center_x = 1;
        const Image a = draw(cut);
        const Image b = draw(inside);
        for (int row = 0; row < kHeight; ++row) {
            for (int column = 140; column < kWidth; ++column) {
                const Pixel expected = pixel_at(b.view(), column - 10, row);
                const Pixel actual = pixel_at(a.view(), column, row);
                for (int c = 0; c < 4; ++c) {
                    ASSERT_NEAR(actual[c], expected[c], 1)
                        << "column " << column << ", row " << row << ", channel " << c;
                }
            }
        }
    }

    std::optional<Renderer> renderer_;
};

TEST_F(RendererGLTest, EmptyFrameIsExactlyTheBackground) {
    const Image image = draw(empty_frame());
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    ASSERT_EQ(image.rgba.size(), std::size_t{4} * kWidth * kHeight);
    for (int row = 0; row < kHeight; ++row) {
        for (int column = 0; column < kWidth; ++column) {
            ASSERT_EQ(pixel_at(image.view(), column, row), opaque(kBackground))
                << "at " << column << "," << row;
        }
    }
}

// A translucent background gives an image with that alpha, in straight (not premultiplied)
// colour: the framebuffer holds premultiplied values, so the colour comes back through one
// rounding to bytes at a quarter of its size, hence the tolerance of 2 per channel.
TEST_F(RendererGLTest, TranslucentBackgroundKeepsItsAlphaAndColour) {
    FrameScene frame = empty_frame();
    frame.background.a = 0.25f;
    const Pixel p = pixel_at(draw(frame).view(), 0, 0);
    const Pixel expected = opaque(kBackground);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c], 2) << "channel " << c;
    EXPECT_EQ(p[3], 64);   // round(0.25 * 255)
}

// Over a fully transparent background an opaque disc is opaque inside, and its anti-aliased
// edge keeps the disc's own colour with partial alpha: no dark fringe from the background's
// colour when the image is composited over something else.
TEST_F(RendererGLTest, DiscEdgesOverATransparentBackgroundKeepTheDiscColour) {
    FrameScene frame = empty_frame();
    frame.background = {1.0f, 1.0f, 1.0f, 0.0f};   // white but invisible: must not leak in
    frame.disc_outlines = false;
    frame.spin_markers = false;
    frame.discs.push_back(disc(0, 0, 3, 0, kRed));
    const Image image = draw(frame);
    EXPECT_EQ(pixel_at(image.view(), 0, 0), (Pixel{0, 0, 0, 0}));
    expect_near_color(pixel_at_world(image.view(), kCamera, 0, 0), opaque(kRed));
    int edge_pixels = 0;
    const int row = kHeight / 2;
    for (int column = 0; column < kWidth; ++column) {
        const Pixel p = pixel_at(image.view(), column, row);
        if (p[3] == 0 || p[3] == 255) continue;
        ++edge_pixels;
        // Unpremultiplying a low alpha magnifies rounding: 255 / alpha units at most.
        const int slack = 1 + 255 / p[3];
        const Pixel red = opaque(kRed);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], red[c], slack) << "column " << column;
    }
    EXPECT_GE(edge_pixels, 2);   // one on each side of the disc
}

PolygonGeom polygon(std::vector<std::pair<float, float>> points, float angle = 0,
                    float rounding = 0) {
    PolygonGeom p{.x = 0, .y = 0, .angle = angle, .vertices = {},
                  .count = static_cast<int>(points.size()), .rounding = rounding, .fill = kRed};
    for (std::size_t i = 0; i < points.size(); ++i) {
        p.vertices[2 * i] = points[i].first;
        p.vertices[2 * i + 1] = points[i].second;
    }
    return p;
}

// Bodies of other shapes are filled exactly inside their outline (rotated, rounded, or a
// capsule's swept segment) and leave the background untouched a pixel beyond it. At 10 pixels
// per metre the darker rim and the anti-aliasing ramp take 0.25 m, so "inside" points are
// deeper than that.
TEST_F(RendererGLTest, PolygonsFillTheirOutlineAndNothingElse) {
    const auto check = [&](const PolygonGeom& shape, std::vector<std::pair<float, float>> in,
                           std::vector<std::pair<float, float>> out) {
        FrameScene frame = empty_frame();
        frame.spin_markers = false;   // PolygonSpinMarkerFollowsTheAngle looks at it
        frame.polygons.push_back(shape);
        const Image image = draw(frame);
        for (const auto& [x, y] : in) {
            SCOPED_TRACE(::testing::Message() << "inside at " << x << ", " << y);
            expect_near_color(pixel_at_world(image.view(), kCamera, x, y), opaque(kRed));
        }
        for (const auto& [x, y] : out) {
            EXPECT_EQ(pixel_at_world(image.view(), kCamera, x, y), opaque(kBackground))
                << x << ", " << y;
        }
    };
    // A 4 m x 2 m box.
    check(polygon({{-2, -1}, {2, -1}, {2, 1}, {-2, 1}}), {{0, 0}, {1.7f, 0.7f}, {-1.7f, -0.7f}},
          {{2.3f, 0}, {0, 1.3f}, {-2.2f, -1.2f}});
    // A 2 m square turned 45 degrees: a diamond reaching 1.41 m along the axes.
    check(polygon({{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, std::numbers::pi_v<float> / 4),
          {{0.8f, 0}, {0, -0.8f}}, {{0.9f, 0.9f}, {1.7f, 0}});
    // A capsule: the segment from (-1, 0) to (1, 0) swept by 0.5 m.
    check(polygon({{-1, 0}, {1, 0}}, 0, 0.5f), {{1.1f, 0}, {0, 0.1f}, {-1.1f, -0.1f}},
          {{0, 0.7f}, {1.4f, 0.4f}, {1.7f, 0}});
    // A rounded box: core 2 m x 1 m, rounding 0.3 m; the corner is cut round.
    check(polygon({{-1, -0.5f}, {1, -0.5f}, {1, 0.5f}, {-1, 0.5f}}, 0, 0.3f),
          {{0.8f, 0}, {0, 0.4f}}, {{1.3f, 0.8f}, {1.45f, 0}, {0, 1.0f}});
}

// As on discs, a contrasting spoke from the centroid along the body's x axis shows its spin;
// a static body is drawn darker and has none.
TEST_F(RendererGLTest, PolygonSpinMarkerFollowsTheAngle) {
    const std::vector<std::pair<float, float>> box{{-2, -1}, {2, -1}, {2, 1}, {-2, 1}};
    for (const float angle : {0.0f, std::numbers::pi_v<float> / 2}) {
        FrameScene frame = empty_frame();
        frame.polygons.push_back(polygon(box, angle));
        const Image image = draw(frame);
        const float c = std::cos(angle), s = std::sin(angle);
        const Pixel marker = pixel_at_world(image.view(), kCamera, 0.8f * c, 0.8f * s);
        EXPECT_GT(std::abs(channel_sum(marker) - channel_sum(opaque(kRed))), 150) << angle;
        // Behind the centroid and across the axis: the fill.
        expect_near_color(pixel_at_world(image.view(), kCamera, -0.8f * c, -0.8f * s),
                          opaque(kRed));
        expect_near_color(pixel_at_world(image.view(), kCamera, -0.5f * s, 0.5f * c),
                          opaque(kRed));
    }
    FrameScene frame = empty_frame();
    PolygonGeom peg = polygon(box);
    peg.is_static = true;
    frame.polygons.push_back(peg);
    const Image image = draw(frame);
    const Pixel core = pixel_at_world(image.view(), kCamera, 0.8f, 0);
    EXPECT_EQ(core, pixel_at_world(image.view(), kCamera, -0.8f, 0));   // no marker
    EXPECT_LT(channel_sum(core) + 60, channel_sum(opaque(kRed)));        // darker
}

TEST_F(RendererGLTest, CornersKeepTheClearColourAroundADisc) {
    FrameScene frame = empty_frame();
    frame.discs.push_back(disc(0, 0, 3, 0, kRed));
    const Image image = draw(frame);
    for (auto [column, row] : {std::pair{0, 0}, {kWidth - 1, 0}, {0, kHeight - 1},
                               {kWidth - 1, kHeight - 1}}) {
        EXPECT_EQ(pixel_at(image.view(), column, row), opaque(kBackground));
    }
}

TEST_F(RendererGLTest, DiscInteriorIsItsFillColourAndTheSpokePointsAlongTheAngle) {
    FrameScene frame = empty_frame();
    // Angles count counter-clockwise from +x with y up: pi/2 points to the image top.
    frame.discs.push_back(disc(0, 0, 3, std::numbers::pi_v<float> / 2, kRed));
    const Image image = draw(frame);
    const ImageView view = image.view();

    expect_near_color(pixel_at_world(view, kCamera, 0, -1.5), opaque(kRed));
    expect_near_color(pixel_at_world(view, kCamera, -1.5, 0), opaque(kRed));
    expect_near_color(pixel_at_world(view, kCamera, 1.5, 0), opaque(kRed));
    const Pixel spoke = pixel_at_world(view, kCamera, 0, 1.5);
    EXPECT_GT(std::abs(channel_sum(spoke) - channel_sum(opaque(kRed))), 150)
        << "the spin marker must contrast with the fill";
}

TEST_F(RendererGLTest, SpokeFollowsTheAngle) {
    FrameScene frame = empty_frame();
    frame.discs.push_back(disc(0, 0, 3, 0, kRed));
    const Image image = draw(frame);
    const ImageView view = image.view();
    expect_near_color(pixel_at_world(view, kCamera, 0, 1.5), opaque(kRed));
    EXPECT_NE(pixel_at_world(view, kCamera, 1.5, 0), opaque(kRed));
}

TEST_F(RendererGLTest, DiscHasADarkerOutline) {
    FrameScene frame = empty_frame();
    frame.discs.push_back(disc(0, 0, 3, 0, kRed));
    const Image image = draw(frame);
    // 1.5 pixels inside the 30-pixel radius, on the side away from the spoke.
    const Pixel rim = pixel_at_world(image.view(), kCamera, -2.85, 0.05);
    EXPECT_LT(channel_sum(rim) + 30, channel_sum(opaque(kRed)));
    EXPECT_EQ(rim[3], 255);
}

TEST_F(RendererGLTest, CameraMapsMetresToPixelsAroundItsCentre) {
    FrameScene frame = empty_frame();
    frame.camera = {.center_x = 100, .center_y = -50, .height = 9};
    frame.discs.push_back(disc(100, -50, 2, 0, kRed));   // 20 pixels radius at the image centre
    const Image image = draw(frame);
    const ImageView view = image.view();
    const int centre_row = kHeight / 2;
    const int centre_column = kWidth / 2;
    expect_near_color(pixel_at(view, centre_column - 10, centre_row), opaque(kRed));
    EXPECT_NE(pixel_at(view, centre_column - 18, centre_row), opaque(kBackground));
    EXPECT_EQ(pixel_at(view, centre_column - 22, centre_row), opaque(kBackground));
    EXPECT_NE(pixel_at(view, centre_column, centre_row - 18), opaque(kBackground));
    EXPECT_EQ(pixel_at(view, centre_column, centre_row - 22), opaque(kBackground));
    EXPECT_EQ(pixel_at(view, centre_column, centre_row + 22), opaque(kBackground));
}

TEST_F(RendererGLTest, UpperWorldLandsInTheTopRowsAndPositiveXOnTheRight) {
    FrameScene frame = empty_frame();
    frame.discs.push_back(disc(4, 2.25f, 1, std::numbers::pi_v<float>, kRed));
    const Image image = draw(frame);
    const ImageView view = image.view();
    // x = 4 m is column 80 + 40; y = +2.25 m is row 45 - 22.5 (rows count from the top).
    expect_near_color(pixel_at(view, 125, 22), opaque(kRed));
    EXPECT_EQ(pixel_at(view, 125, 67), opaque(kBackground));
    EXPECT_EQ(pixel_at(view, 35, 22), opaque(kBackground));
}

TEST_F(RendererGLTest, LaterDiscsAreDrawnOnTop) {
    FrameScene frame = empty_frame();
    frame.discs.push_back(disc(0, 0, 3, 0, kRed));
    frame.discs.push_back(disc(0, 0, 2, 0, kBlue));
    const Image image = draw(frame);
    expect_near_color(pixel_at_world(image.view(), kCamera, -1, 0), opaque(kBlue));
    expect_near_color(pixel_at_world(image.view(), kCamera, -2.5, 0), opaque(kRed));
}

// The renderer draws most discs as point sprites, but GL drops a point whose centre is outside
// the view: those discs are drawn as quads instead, and must look the same.
TEST_F(RendererGLTest, ADiscCutByTheFrameEdgeIsDrawnLikeOneInside) {
    // Centre 3 pixels beyond the right edge (x = 8 m), spoke pointing back into the frame.
    FrameScene cut = empty_frame();
    cut.discs.push_back(disc(8.3f, 0, 1.5f, std::numbers::pi_v<float>, kRed));
    expect_near_color(pixel_at_world(draw(cut).view(), kCamera, 7.9, 1.0), opaque(kRed));
    expect_same_further_in(cut);
}

// Polygons too are point sprites where they fit and quads where not (a centre beyond the edge):
// a turned box cut by the frame's edge looks as it does further in.
TEST_F(RendererGLTest, APolygonCutByTheFrameEdgeIsDrawnLikeOneInside) {
    FrameScene cut = empty_frame();
    PolygonGeom box = polygon({{-1, -0.6f}, {1, -0.6f}, {1, 0.6f}, {-1, 0.6f}}, 0.4f, 0.1f);
    box.x = 8.3f;
    cut.polygons.push_back(box);
    expect_near_color(pixel_at_world(draw(cut).view(), kCamera, 7.6, 0.2), opaque(kRed));
    expect_same_further_in(cut);
}

TEST_F(RendererGLTest, DiscsDrawnAsQuadsAndAsPointsKeepTheirOrder) {
    // Red's centre is outside the frame (a quad); blue's is inside (a point sprite).
    FrameScene blue_on_top = empty_frame();
    blue_on_top.discs.push_back(disc(8.5f, 0, 2, 0, kRed));
    blue_on_top.discs.push_back(disc(6.5f, 0, 1, 0, kBlue));
    FrameScene red_on_top = blue_on_top;
    std::swap(red_on_top.discs[0], red_on_top.discs[1]);
    expect_near_color(pixel_at_world(draw(blue_on_top).view(), kCamera, 7.05, 0.35),
                      opaque(kBlue));
    expect_near_color(pixel_at_world(draw(red_on_top).view(), kCamera, 7.05, 0.35),
                      opaque(kRed));
}

// GL caps a point sprite's size (255 pixels on llvmpipe): a bigger disc must not be cut square.
TEST(RendererBigDiscGLTest, ADiscWiderThanAnyPointSpriteIsDrawnWhole) {
    auto renderer = Renderer::create({.width = 400, .height = 300});
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    FrameScene frame = empty_frame();
    frame.camera = {.center_x = 0, .center_y = 0, .height = 3};   // 100 pixels per metre
    frame.discs.push_back(disc(0, 0, 1.4f, std::numbers::pi_v<float> / 2, kRed));
    auto image = renderer->draw(frame);
    ASSERT_TRUE(image.ok()) << image.error().message;
    // 135 pixels out along the axes and the diagonal, inside the outline: the fill colour.
    for (const auto& [x, y] : {std::pair{1.35, 0.0}, {-1.35, 0.0}, {0.0, -1.35}, {0.95, 0.95}}) {
        expect_near_color(pixel_at_world(*image, frame.camera, x, y), opaque(kRed));
    }
    EXPECT_EQ(pixel_at_world(*image, frame.camera, 1.45, 0), opaque(kBackground));
}

TEST_F(RendererGLTest, CapsulesCoverTheirSegmentAndRoundEndsAndLieUnderDiscs) {
    FrameScene frame = empty_frame();
    frame.capsules.push_back({.ax = -4, .ay = 0, .bx = 4, .by = 0, .radius = 0.5f, .color = kWall});
    frame.capsules.push_back({.ax = 6, .ay = -3, .bx = 6, .by = 3, .radius = 0.5f, .color = kWall});
    frame.discs.push_back(disc(-3, 0, 0.6f, 0, kBlue));
    const Image image = draw(frame);
    const ImageView view = image.view();
    expect_near_color(pixel_at_world(view, kCamera, 0.05, 0.05), opaque(kWall));
    expect_near_color(pixel_at_world(view, kCamera, 6.05, 2.45), opaque(kWall));
    expect_near_color(pixel_at_world(view, kCamera, -3.25, 0.05), opaque(kBlue));
    EXPECT_NE(pixel_at_world(view, kCamera, 4.25, 0.05), opaque(kBackground));   // round end
    EXPECT_EQ(pixel_at_world(view, kCamera, 4.75, 0.05), opaque(kBackground));
    EXPECT_EQ(pixel_at_world(view, kCamera, 0.05, 1.05), opaque(kBackground));
    EXPECT_EQ(pixel_at_world(view, kCamera, 6.05, 3.75), opaque(kBackground));
}

TEST_F(RendererGLTest, StaticDiscsHaveADarkerCoreAndNoSpoke) {
    FrameScene frame = empty_frame();
    frame.discs.push_back(disc(0, 0, 3, 0, kRed, /*is_static=*/true));
    const Image image = draw(frame);
    const ImageView view = image.view();
    const Pixel core = pixel_at_world(view, kCamera, 0.05, 0.05);
    EXPECT_LT(channel_sum(core) + 100, channel_sum(opaque(kRed)));
    // A uniform core: nothing marks an angle where a moving disc would have its spoke.
    for (auto [dx, dy] : {std::pair{1.5, 0.0}, {-1.5, 0.0}, {0.0, 1.5}, {0.0, -1.5}}) {
        EXPECT_EQ(pixel_at_world(view, kCamera, 0.05 + dx, 0.05 + dy), core) << dx << "," << dy;
    }
}

TEST_F(RendererGLTest, SubPixelDiscsStayVisible) {
    FrameScene frame = empty_frame();
    frame.discs.push_back(disc(0.05f, 0.05f, 0.001f, 0, kRed));   // 0.01 px radius, pixel centre
    const Image image = draw(frame);
    EXPECT_NE(pixel_at_world(image.view(), kCamera, 0.05, 0.05), opaque(kBackground));
}

FrameScene busy_frame() {
    FrameScene frame = empty_frame();
    frame.capsules.push_back({.ax = -7, .ay = -4, .bx = 7, .by = 3, .radius = 0.3f, .color = kWall});
    for (int i = 0; i < 40; ++i) {
        const float x = -7.0f + 0.37f * static_cast<float>(i);
        const float y = 3.0f * std::sin(0.7f * static_cast<float>(i));
        Rgba fill = (i % 2 == 0) ? kRed : kBlue;
        fill.a = (i % 3 == 0) ? 0.5f : 1.0f;
        frame.discs.push_back(disc(x, y, 0.2f + 0.05f * static_cast<float>(i % 7),
                                   0.3f * static_cast<float>(i), fill, i % 5 == 0));
    }
    return frame;
}

TEST_F(RendererGLTest, EveryPixelIsOpaqueEvenUnderTranslucentDiscsAndEdges) {
    const Image image = draw(busy_frame());
    ASSERT_FALSE(image.rgba.empty());
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) {
        ASSERT_EQ(image.rgba[i], 255) << "pixel " << i / 4;
    }
}

TEST_F(RendererGLTest, SameFrameTwiceGivesIdenticalBytes) {
    const Image first = draw(busy_frame());
    (void)draw(empty_frame());
    const Image second = draw(busy_frame());
    EXPECT_EQ(first.rgba, second.rgba);
}

TEST_F(RendererGLTest, TwoRenderersGiveIdenticalBytes) {
    auto other = Renderer::create({.width = kWidth, .height = kHeight});
    ASSERT_TRUE(other.ok()) << other.error().message;
    // Interleaved, so each draw has to switch to its own context.
    const Image mine = draw(busy_frame());
    auto theirs = other->draw(busy_frame());
    ASSERT_TRUE(theirs.ok()) << theirs.error().message;
    const std::vector<std::uint8_t> their_bytes(theirs->rgba.begin(), theirs->rgba.end());
    EXPECT_EQ(mine.rgba, draw(busy_frame()).rgba);
    EXPECT_EQ(mine.rgba, their_bytes);
}

TEST_F(RendererGLTest, MovedRendererKeepsDrawing) {
    Renderer moved = std::move(*renderer_);
    renderer_.reset();
    auto view = moved.draw(empty_frame());
    ASSERT_TRUE(view.ok()) << view.error().message;
    EXPECT_EQ(pixel_at(*view, 3, 3), opaque(kBackground));
}

TEST_F(RendererGLTest, NonPositiveCameraHeightIsAnError) {
    FrameScene frame = empty_frame();
    frame.camera.height = 0;
    auto view = renderer_->draw(frame);
    ASSERT_FALSE(view.ok());
    EXPECT_EQ(view.error().message, "camera height must be a positive number of metres");
}

TEST_F(RendererGLTest, RendererInfoNamesACoreProfileContext) {
    EXPECT_THAT(renderer_->renderer_info(), HasSubstr("(Core Profile)"));
}

TEST(RendererCreateGLTest, RejectsNonPositiveSizes) {
    auto created = Renderer::create({.width = 0, .height = 720});
    ASSERT_FALSE(created.ok());
    EXPECT_EQ(created.error().message, "renderer size must be positive, got 0x720");
}

TEST(RendererCreateGLTest, RejectsSizesBeyondTheGLLimit) {
    auto created = Renderer::create({.width = 1'000'000, .height = 720});
    ASSERT_FALSE(created.ok());
    EXPECT_THAT(created.error().message,
                HasSubstr("renderer size 1000000x720 exceeds the GL limit of "));
}

}  // namespace
}  // namespace discreel::render

#include "frame_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "../render/golden_check.hpp"
#include "discreel/shapes.hpp"

namespace discreel::job {
namespace {

scene::Scene boxed_scene() {
    scene::Scene s;
    s.video.width = 1280;
    s.video.height = 720;
    scene::Wall box;
    box.shape = scene::Wall::Shape::box;
    box.a = {0, 0};
    box.b = {12.8, 7.2};
    box.thickness = 0.02;
    s.walls.push_back(box);
    return s;
}

TEST(FitCameraTest, FramesWallsWithFivePercentMargin) {
    const render::Camera camera = fit_camera(boxed_scene());
    EXPECT_DOUBLE_EQ(camera.center_x, 6.4);
    EXPECT_DOUBLE_EQ(camera.center_y, 3.6);
    // The box plus its wall thickness on each side, 7.24 m tall, and 5 % more on each side.
    EXPECT_NEAR(camera.height, 7.24 * 1.1, 1e-12);
}

TEST(FitCameraTest, WideContentWidensTheView) {
    scene::Scene s = boxed_scene();
    s.walls[0].b = {25.6, 7.2};   // twice as wide as the 16:9 frame at this height
    const render::Camera camera = fit_camera(s);
    EXPECT_NEAR(camera.height, 25.64 * 1.1 * 720 / 1280, 1e-12);
}

TEST(FitCameraTest, SceneCameraWins) {
    scene::Scene s = boxed_scene();
    s.camera.center = Vec2{1, 2};
    s.camera.height = 3;
    const render::Camera camera = fit_camera(s);
    EXPECT_EQ(camera.center_x, 1);
    EXPECT_EQ(camera.center_y, 2);
    EXPECT_EQ(camera.height, 3);
}

TEST(FitCameraTest, WithoutWallsFramesTheDiscs) {
    scene::Scene s;
    s.video.width = 100;
    s.video.height = 100;
    scene::Body d;
    d.position = {5, 5};
    d.radius = 1;
    s.bodies.push_back(d);
    const render::Camera camera = fit_camera(s);
    EXPECT_DOUBLE_EQ(camera.center_x, 5);
    EXPECT_NEAR(camera.height, 2 * 1.1, 1e-12);
}

TEST(FitCameraTest, AStackOnAGroundSegmentIsNotCutOff) {
    // A ground segment 10 m wide at y = 0 and a tower of 1 m boxes up to y = 8, turned a
    // quarter: the view holds the tower's top (its outline, not its bounding circle).
    scene::Scene s;
    s.video.width = 1280;
    s.video.height = 720;
    scene::Wall ground;
    ground.a = {-5, 0};
    ground.b = {5, 0};
    ground.thickness = 0.1;
    s.walls.push_back(ground);
    for (int k = 0; k < 8; ++k) {
        scene::Body b;
        b.shape = physics::box_shape(1, 1).value();
        b.radius = physics::bounding_radius(*b.shape);
        b.position = {0, 0.5 + k};
        b.angle = std::numbers::pi / 2;
        s.bodies.push_back(b);
    }
    const render::Camera camera = fit_camera(s);
    EXPECT_NEAR(camera.center_y, (8 - 0.1) / 2, 1e-9);
    EXPECT_NEAR(camera.height, 8.1 * 1.1, 1e-9);
}

TEST(FrameSceneBuilderTest, BoxBecomesFourCapsulesOutsideTheCorners) {
    scene::Scene s = boxed_scene();
    s.walls[0].thickness = 0.2;
    FrameSceneBuilder builder(s);
    const render::FrameScene& frame = builder.build(0, {});
    ASSERT_EQ(frame.capsules.size(), 4u);
    // The bottom wall's centre line sits half a thickness below the floor, so its inner edge
    // is exactly where discs rest.
    EXPECT_FLOAT_EQ(frame.capsules[0].ay, -0.1f);
    EXPECT_FLOAT_EQ(frame.capsules[0].radius, 0.1f);
    EXPECT_FLOAT_EQ(frame.capsules[0].ax, -0.1f);
    EXPECT_FLOAT_EQ(frame.capsules[0].bx, 12.9f);
}

TEST(FrameSceneBuilderTest, DiscsFollowTheStateWithTheirLook) {
    scene::Scene s = boxed_scene();
    scene::Body d;
    d.radius = 0.5;
    d.color = {255, 0, 0, 255};
    d.is_static = true;
    s.bodies.push_back(d);
    FrameSceneBuilder builder(s);
    physics::BodyState state;
    state.position = {3, 4};
    state.angle = 1.5;
    const render::FrameScene& frame = builder.build(0, {&state, 1});
    ASSERT_EQ(frame.discs.size(), 1u);
    EXPECT_EQ(frame.discs[0].x, 3.0f);
    EXPECT_EQ(frame.discs[0].y, 4.0f);
    EXPECT_EQ(frame.discs[0].angle, 1.5f);
    EXPECT_EQ(frame.discs[0].radius, 0.5f);
    EXPECT_EQ(frame.discs[0].fill.r, 1.0f);
    EXPECT_EQ(frame.discs[0].fill.g, 0.0f);
    EXPECT_TRUE(frame.discs[0].is_static);
}

// A scene of `n` discs at 60 fps, 1280x720, no walls: the builder only needs looks and style.
scene::Scene discs_scene(std::size_t n) {
    scene::Scene s = boxed_scene();
    for (std::size_t i = 0; i < n; ++i) {
        scene::Body d;
        d.id = std::to_string(i);
        d.id.insert(d.id.begin(), 'd');
        d.radius = 0.5;
        d.color = {200, 100, 50, 255};
        s.bodies.push_back(d);
    }
    return s;
}

physics::BodyState at(double x, double y, double vx = 0, double vy = 0) {
    physics::BodyState d;
    d.position = {x, y};
    d.velocity = {vx, vy};
    return d;
}

TEST(CameraMoveTest, KeysAreEasedBetweenAndHeldBeyond) {
    // At 60 fps: from (0, 0), 10 m tall at t = 1 to (10, 0), 4 m at t = 3, then following
    // disc 1 (at (20, 6)) from t = 4, the height kept.
    scene::Scene s = discs_scene(2);
    s.camera.keys = {{.t = 1, .center = Vec2{0, 0}, .follow = {}, .height = 10},
                     {.t = 3, .center = Vec2{10, 0}, .follow = {}, .height = 4},
                     {.t = 4, .center = {}, .follow = 1, .height = {}}};
    s.camera.ease = scene::Ease::linear;
    const std::vector states{at(0, 0), at(20, 6)};
    const auto camera_at = [&](int frame) {
        FrameSceneBuilder builder(s);
        for (int f = 0; f < frame; ++f) builder.observe(f, states);
        return builder.build(frame, states).camera;
    };
    render::Camera c = camera_at(30);   // before the first key: held
    EXPECT_DOUBLE_EQ(c.center_x, 0);
    EXPECT_DOUBLE_EQ(c.height, 10);
    c = camera_at(120);                 // t = 2, halfway
    EXPECT_NEAR(c.center_x, 5, 1e-12);
    EXPECT_NEAR(c.height, 7, 1e-12);
    c = camera_at(210);                 // t = 3.5, halfway to the follow
    EXPECT_NEAR(c.center_x, 15, 1e-12);
    EXPECT_NEAR(c.center_y, 3, 1e-12);
    EXPECT_NEAR(c.height, 4, 1e-12);
    c = camera_at(300);                 // after the last key: following
    EXPECT_NEAR(c.center_x, 20, 1e-12);
    EXPECT_NEAR(c.center_y, 6, 1e-12);
    // Eased in and out: a quarter of the way in time is 5/32 of the way in space.
    s.camera.ease = scene::Ease::in_out;
    EXPECT_NEAR(camera_at(90).center_x, 10 * 5.0 / 32, 1e-12);
}

TEST(FollowCameraTest, WithoutLagTheDiscIsAlwaysCentred) {
    scene::Scene s = discs_scene(2);
    s.camera.follow = 1;
    s.camera.follow_lag = 0;
    FrameSceneBuilder builder(s);
    for (int frame = 0; frame < 5; ++frame) {
        const std::vector<physics::BodyState> states{at(0, 0), at(1.5 * frame, -frame)};
        const render::FrameScene& f = builder.build(frame, states);
        EXPECT_EQ(f.camera.center_x, 1.5 * frame);
        EXPECT_EQ(f.camera.center_y, -frame);
        EXPECT_EQ(f.camera.height, fit_camera(s).height);   // only the centre follows
    }
}

// The disc jumps 10 m at t = 0+ and stays: the camera closes the gap as 1 - exp(-t / lag),
// at any frame rate, and whether the frames in between are drawn or only observed.
TEST(FollowCameraTest, SmoothingClosesAGapExponentiallyAtAnyFrameRate) {
    for (const int fps : {30, 60, 240}) {
        scene::Scene s = discs_scene(1);
        s.video.fps = fps;
        s.camera.follow = 0;
        s.camera.follow_lag = 0.25;
        FrameSceneBuilder builder(s);
        const std::vector<physics::BodyState> start{at(0, 0)}, moved{at(10, 0)};
        builder.observe(0, start);
        const int half_second = fps / 2;
        for (int frame = 1; frame < half_second; ++frame) builder.observe(frame, moved);
        const render::FrameScene& f = builder.build(half_second, moved);
        SCOPED_TRACE(fps);
        EXPECT_NEAR(f.camera.center_x, 10 * (1 - std::exp(-0.5 / 0.25)), 1e-9);
        EXPECT_EQ(f.camera.center_y, 0);
    }
}

// A disc on a circle: once the start has faded, the camera trails it by the steady-state
// error of the sampled exponential filter, r |1 - H(e^{i w dt})| with
// H(z) = a / (1 - (1 - a) / z), a = 1 - exp(-dt / lag): within a metre, so the disc stays
// near the middle of a 6 m view.
TEST(FollowCameraTest, KeepsACirclingDiscNearTheCentre) {
    const double r = 3, w = 2, lag = 0.15;
    const int fps = 30;
    scene::Scene s = discs_scene(1);
    s.video.fps = fps;
    s.camera.follow = 0;
    s.camera.follow_lag = lag;
    FrameSceneBuilder builder(s);
    const double dt = 1.0 / fps;
    const double a = 1 - std::exp(-dt / lag);
    const std::complex<double> z = std::polar(1.0, w * dt);
    const double expected = r * std::abs(1.0 - a / (1.0 - (1.0 - a) / z));
    for (int frame = 0; frame <= 90; ++frame) {
        const double t = frame * dt;
        const std::vector<physics::BodyState> states{at(r * std::cos(w * t), r * std::sin(w * t))};
        const render::FrameScene& f = builder.build(frame, states);
        if (frame < 60) continue;   // 2 s = 13 lags: the start is forgotten to 1e-5
        const double gap = std::hypot(f.camera.center_x - states[0].position.x,
                                      f.camera.center_y - states[0].position.y);
        EXPECT_NEAR(gap, expected, 1e-4) << "frame " << frame;
        EXPECT_LT(gap, 1.0);
    }
}

TEST(TrailsTest, KeepTheirLengthFadeTowardTheBackgroundAndSkipPegsAndRestingDiscs) {
    scene::Scene s = discs_scene(3);
    s.bodies[1].is_static = true;
    s.style.trails = {.enabled = true, .length = 0.5, .fade = true, .width = 0.4};
    FrameSceneBuilder builder(s);
    const render::FrameScene* f = nullptr;
    for (int frame = 0; frame < 100; ++frame) {
        const std::vector<physics::BodyState> states{at(0.1 * frame, 0), at(5, 5), at(-3, -3)};
        f = &builder.build(frame, states);
    }
    // 0.5 s at 60 fps: 30 segments, oldest first, the newest ending at the disc.
    ASSERT_EQ(f->trails.size(), 30u);
    EXPECT_FLOAT_EQ(f->trails.back().bx, 9.9f);
    EXPECT_FLOAT_EQ(f->trails.back().ax, 9.8f);
    EXPECT_FLOAT_EQ(f->trails.front().ax, 6.9f);
    // Fading: older segments are thinner and closer to the background colour.
    EXPECT_LT(f->trails.front().radius, f->trails.back().radius);
    EXPECT_LE(f->trails.back().radius, 0.4f * 0.5f);
    const float background_r = f->background.r;
    EXPECT_LT(std::abs(f->trails.front().color.r - background_r),
              std::abs(f->trails.back().color.r - background_r));
    EXPECT_EQ(f->trails.back().color.a, 1.0f);
}

TEST(TrailsTest, WithoutFadeKeepOneWidthAndColour) {
    scene::Scene s = discs_scene(1);
    s.style.trails = {.enabled = true, .length = 0.1, .fade = false, .width = 0.5};
    FrameSceneBuilder builder(s);
    const render::FrameScene* f = nullptr;
    for (int frame = 0; frame < 20; ++frame) f = &builder.build(frame, std::vector{at(frame, 0)});
    ASSERT_EQ(f->trails.size(), 6u);   // ceil(0.1 s * 60 fps)
    for (const render::LineGeom& l : f->trails) {
        EXPECT_FLOAT_EQ(l.radius, 0.25f);
        EXPECT_EQ(l.color.r, f->trails[0].color.r);
    }
}

TEST(TrailsTest, MemoryIsBoundedByShorteningTrails) {
    scene::Scene s = discs_scene(max_trail_points / 4);
    s.style.trails = {.enabled = true, .length = 10, .fade = true, .width = 0.4};
    FrameSceneBuilder builder(s);
    const std::vector<physics::BodyState> still(s.bodies.size(), at(0, 0));
    std::vector<physics::BodyState> moved = still;
    moved[0] = at(1, 0);
    builder.observe(0, still);
    for (int frame = 1; frame < 10; ++frame) builder.observe(frame, frame % 2 ? moved : still);
    // Four points per disc fit the budget: three segments, not 10 s worth.
    EXPECT_EQ(builder.build(10, still).trails.size(), 3u);
}

TEST(TrailsTest, ARespawnedBodyStartsANewTrail) {
    // Disc 0 runs right along y = 0; at frame 10 a respawn puts a new disc 0 at (0, 5): its
    // trail starts there, never a segment from the old disc's last point.
    scene::Scene s = discs_scene(1);
    s.style.trails = {.enabled = true, .length = 1, .fade = false, .width = 0.4};
    s.respawns.push_back({.at = 10.0 / 60, .first = 0, .bodies = {s.bodies[0]}});
    FrameSceneBuilder builder(s);
    const render::FrameScene* f = nullptr;
    for (int frame = 0; frame < 10; ++frame) f = &builder.build(frame, std::vector{at(frame, 0)});
    EXPECT_EQ(f->trails.size(), 9u);
    builder.respawned(1);
    for (int frame = 10; frame < 14; ++frame) {
        f = &builder.build(frame, std::vector{at(frame - 10, 5)});
    }
    // The old trail's nine segments stay behind (they fade as usual); the new disc has three,
    // all at y = 5.
    std::size_t new_trail = 0;
    for (const render::LineGeom& l : f->trails) {
        EXPECT_FALSE(l.ay != l.by) << "a segment joins the old disc to the new: " << l.ay;
        new_trail += l.ay == 5.0f ? 1 : 0;
    }
    EXPECT_EQ(new_trail, 3u);
}

TEST(TrailsTest, AShapesTrailIsAsWideAsItsOutlineAcrossItsMotion) {
    // A 1.2 x 0.3 m plank: moving lengthwise its trail is 0.3 m wide (times the style's
    // width), broadside 1.2 m, whatever its bounding circle.
    for (const auto& [angle, across] : {std::pair{0.0, 0.3}, std::pair{std::numbers::pi / 2, 1.2}}) {
        scene::Scene s = discs_scene(1);
        s.bodies[0].shape = physics::box_shape(1.2, 0.3).value();
        s.bodies[0].radius = physics::bounding_radius(*s.bodies[0].shape);
        s.style.trails = {.enabled = true, .length = 0.1, .fade = false, .width = 0.5};
        FrameSceneBuilder builder(s);
        const render::FrameScene* f = nullptr;
        for (int frame = 0; frame < 5; ++frame) {
            physics::BodyState b = at(0.1 * frame, 0);
            b.angle = angle;
            f = &builder.build(frame, std::vector{b});
        }
        ASSERT_FALSE(f->trails.empty());
        for (const render::LineGeom& l : f->trails) {
            EXPECT_NEAR(l.radius, 0.5 * across / 2, 1e-6) << angle;
        }
    }
}

TEST(VelocityArrowsTest, AfterContactShowFromEachContactAndFadeOut) {
    // Arrows for 0.5 s after a contact: disc 0 touched at t = 0.1, disc 1 never, disc 2 at
    // t = 0.5. At frame 30 (t = 0.5) disc 0's arrow is at (1 - 0.4 / 0.5) of its alpha, disc
    // 2's whole.
    scene::Scene s = discs_scene(3);
    s.style.velocity_arrows = {.enabled = true, .scale = 0.5, .color = {255, 255, 255, 255},
                               .width = 2, .after_contact = 0.5};
    FrameSceneBuilder builder(s);
    const std::vector<double> contacts{0.1, -HUGE_VAL, 0.5};
    const std::vector states{at(0, 0, 1, 0), at(2, 0, 1, 0), at(4, 0, 1, 0)};
    for (int frame = 0; frame < 30; ++frame) builder.observe(frame, states);
    const render::FrameScene& f = builder.build(30, states, contacts);
    ASSERT_EQ(f.arrows.size(), 2u);
    EXPECT_EQ(f.arrows[0].tail_x, 0.0f);
    EXPECT_NEAR(f.arrows[0].color.a, 0.2, 1e-6);
    EXPECT_EQ(f.arrows[1].tail_x, 4.0f);
    EXPECT_EQ(f.arrows[1].color.a, 1.0f);
    // Disc 0's is gone once 0.5 s have passed.
    for (int frame = 31; frame < 36; ++frame) builder.observe(frame, states);
    const render::FrameScene& later = builder.build(36, states, contacts);
    ASSERT_EQ(later.arrows.size(), 1u);
    EXPECT_EQ(later.arrows[0].tail_x, 4.0f);
}

TEST(FlashTest, ABodyBrightensAtItsContactAndFadesBack) {
    // style.flash 0.2 s: disc 0 touched at t = 0.5 is 70 % of the way to white then, half of
    // that 0.1 s later, and its own colour once 0.2 s have passed (frame 43); disc 1, never
    // touched, keeps its own.
    scene::Scene s = discs_scene(2);
    s.style.flash = 0.2;
    FrameSceneBuilder builder(s);
    const std::vector<double> contacts{0.5, -HUGE_VAL};
    const std::vector states{at(0, 0), at(2, 0)};
    const float own = 200 / 255.0f;
    for (int frame = 0; frame < 30; ++frame) builder.observe(frame, states);
    const render::FrameScene* f = &builder.build(30, states, contacts);
    EXPECT_NEAR(f->discs[0].fill.r, own + (1 - own) * 0.7f, 1e-6);
    EXPECT_EQ(f->discs[1].fill.r, own);
    for (int frame = 31; frame < 36; ++frame) builder.observe(frame, states);
    f = &builder.build(36, states, contacts);
    EXPECT_NEAR(f->discs[0].fill.g, 100 / 255.0f + (1 - 100 / 255.0f) * 0.35f, 1e-6);
    for (int frame = 37; frame < 43; ++frame) builder.observe(frame, states);
    EXPECT_EQ(builder.build(43, states, contacts).discs[0].fill.r, own);
}

TEST(TextTest, ReadoutsAreFilledInEachFrameAndOverlaysShowInTheirTime) {
    // Two 1 kg discs: the first at (0, 2) moving at (3, 4), the second at rest at (5, 0).
    // g = (0, -9.81): E = 0.5 * 25 + 9.81 * 2 = 32.12 J; momentum 5 N s.
    scene::Scene s = discs_scene(2);
    for (scene::Body& b : s.bodies) b.mass = 1;
    s.bodies[0].label = {{"v = ", {}},
                         {"", scene::Readout{.kind = scene::Readout::Kind::speed, .body = 0,
                                             .precision = 1}},
                         {" m/s", {}}};
    using Kind = scene::Readout::Kind;
    const auto readout = [](Kind kind, int precision) {
        return scene::TextPart{"", scene::Readout{.kind = kind, .body = 0, .precision = precision}};
    };
    s.overlays.push_back({.text = {{"t=", {}}, readout(Kind::time, 2), {" f=", {}},
                                   readout(Kind::frame, 0), {" E=", {}}, readout(Kind::energy, 2),
                                   {" p=", {}}, readout(Kind::momentum, 1)},
                          .at = {},
                          .anchor = scene::TextAnchor::bottom_right,
                          .size = 0.05,
                          .color = {255, 255, 255, 255},
                          .from = 0.5,
                          .to = 1.0,
                          .fade = 0.25});
    FrameSceneBuilder builder(s);
    const std::vector states{at(0, 2, 3, 4), at(5, 0)};
    for (int frame = 0; frame < 45; ++frame) {
        const render::FrameScene& f = builder.build(frame, states);
        const bool shown = frame >= 30 && frame < 60;
        ASSERT_EQ(f.labels.size(), shown ? 2u : 1u) << frame;
        EXPECT_EQ(f.labels[0].text, "v = 5.0 m/s");
        EXPECT_TRUE(f.labels[0].world);
        EXPECT_EQ(f.labels[0].x, 0);
        if (frame == 36) {   // t = 0.6 s: 0.1 s into a 0.25 s fade
            EXPECT_EQ(f.labels[1].text, "t=0.60 f=36 E=32.12 p=5.0");
            EXPECT_NEAR(f.labels[1].color.a, 0.4, 1e-6);
            EXPECT_EQ(f.labels[1].anchor, render::Anchor::bottom_right);
            EXPECT_FALSE(f.labels[1].world);
        }
    }
}

TEST(VelocityArrowsTest, PointAlongTheVelocityScaledByTheStyle) {
    scene::Scene s = discs_scene(2);
    s.bodies[1].is_static = true;
    s.style.velocity_arrows = {.enabled = true, .scale = 0.5, .color = {0, 255, 0, 255},
                               .width = 3, .after_contact = {}};
    FrameSceneBuilder builder(s);
    const render::FrameScene& f = builder.build(0, std::vector{at(1, 2, 4, -2), at(5, 5)});
    ASSERT_EQ(f.arrows.size(), 1u);   // pegs never move
    EXPECT_EQ(f.arrows[0].tail_x, 1.0f);
    EXPECT_EQ(f.arrows[0].tail_y, 2.0f);
    EXPECT_EQ(f.arrows[0].head_x, 3.0f);
    EXPECT_EQ(f.arrows[0].head_y, 1.0f);
    EXPECT_EQ(f.arrows[0].width, 3.0f);
    EXPECT_EQ(f.arrows[0].color.g, 1.0f);
}

TEST(ClockTest, ShowsTimeFrameOrBothInItsCorner) {
    scene::Scene s = discs_scene(0);
    s.style.clock = {.enabled = true, .corner = scene::Corner::bottom_right,
                     .format = scene::ClockFormat::time, .color = {255, 255, 255, 255}};
    const auto text_at = [&](scene::ClockFormat format, int frame) {
        s.style.clock.format = format;
        FrameSceneBuilder builder(s);
        const render::FrameScene& f = builder.build(frame, {});
        EXPECT_EQ(f.texts.size(), 1u);
        EXPECT_EQ(f.texts[0].corner, render::Corner::bottom_right);
        EXPECT_EQ(f.texts[0].dot, 4);   // 720 rows: 4 pixels a dot, 28-pixel glyphs
        return f.texts[0].text;
    };
    EXPECT_EQ(text_at(scene::ClockFormat::time, 75), "t = 1.25 s");
    EXPECT_EQ(text_at(scene::ClockFormat::frame, 75), "frame 75");
    EXPECT_EQ(text_at(scene::ClockFormat::both, 0), "t = 0.00 s  frame 0");
}

TEST(FrameSceneBuilderTest, DefaultStyleDrawsNoOverlays) {
    scene::Scene s = discs_scene(1);
    FrameSceneBuilder builder(s);
    const render::FrameScene* f = nullptr;
    for (int frame = 0; frame < 3; ++frame)
        f = &builder.build(frame, std::vector{at(frame, 1, 1, 1)});
    EXPECT_TRUE(f->disc_outlines);
    EXPECT_TRUE(f->spin_markers);
    EXPECT_TRUE(f->trails.empty());
    EXPECT_TRUE(f->arrows.empty());
    EXPECT_TRUE(f->texts.empty());
    EXPECT_EQ(f->camera.center_x, fit_camera(s).center_x);
}

// The follow camera golden: 320x180 at 30 fps, a disc circling inside a box among pegs and
// two drifting discs, with trails, velocity arrows and the clock, after 2.5 s. The view is
// 6 m tall and centred (with lag) on the circling disc, so the box's walls slide past.
TEST(FrameSceneGoldenGLTest, FollowCameraWithTrailsArrowsAndClock) {
    scene::Scene s;
    s.video.width = 320;
    s.video.height = 180;
    s.video.fps = 30;
    scene::Wall box;
    box.shape = scene::Wall::Shape::box;
    box.b = {16, 9};
    box.thickness = 0.2;
    s.walls.push_back(box);
    const auto disc = [&](std::string id, double r, scene::Color c, bool is_static) {
        scene::Body d;
        d.id = std::move(id);
        d.radius = r;
        d.color = c;
        d.is_static = is_static;
        s.bodies.push_back(d);
    };
    disc("cue", 0.4, {0xf4, 0xd3, 0x5e, 0xff}, false);
    disc("a", 0.3, {0xe4, 0x57, 0x2e, 0xff}, false);
    disc("b", 0.3, {0x17, 0xbe, 0xbb, 0xff}, false);
    for (int i = 0; i < 6; ++i)
        disc(std::string(1, static_cast<char>('p' + i)), 0.2, {0x88, 0x99, 0xaa, 0xff}, true);
    s.camera.height = 6;
    s.camera.follow = 0;
    s.camera.follow_lag = 0.15;
    s.style.trails = {.enabled = true, .length = 0.6, .fade = true, .width = 0.4};
    s.style.velocity_arrows = {.enabled = true, .scale = 0.15, .color = {255, 255, 255, 255},
                               .width = 1.5, .after_contact = {}};
    s.style.clock = {.enabled = true, .corner = scene::Corner::top_left,
                     .format = scene::ClockFormat::both, .color = {255, 255, 255, 255}};

    FrameSceneBuilder builder(s);
    const int last = 75;
    const render::FrameScene* f = nullptr;
    for (int frame = 0; frame <= last; ++frame) {
        const double t = frame / 30.0, w = 2, r = 3;
        std::vector<physics::BodyState> states{
            at(8 + r * std::cos(w * t), 4.5 + r * std::sin(w * t), -r * w * std::sin(w * t),
               r * w * std::cos(w * t)),
            at(5 + 1.5 * t, 2 + 0.5 * t, 1.5, 0.5),
            at(11 - t, 6.5 - 0.8 * t, -1, -0.8)};
        for (int i = 0; i < 6; ++i) states.push_back(at(5 + 1.2 * i, 4.5 + (i % 2 ? 0.8 : -0.8)));
        for (std::size_t i = 0; i < states.size(); ++i)
            states[i].angle = i == 0 ? w * t : 0.3 * static_cast<double>(i);
        if (frame == last)
            f = &builder.build(frame, states);
        else
            builder.observe(frame, states);
    }
    ASSERT_NE(f, nullptr);
    render::test::check_golden("follow_camera", *f, 320, 180);
}

}  // namespace
}  // namespace discreel::job

#include "frame_scene.hpp"

#include <gtest/gtest.h>

namespace discreel::app {
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
    scene::Disc d;
    d.position = {5, 5};
    d.radius = 1;
    s.discs.push_back(d);
    const render::Camera camera = fit_camera(s);
    EXPECT_DOUBLE_EQ(camera.center_x, 5);
    EXPECT_NEAR(camera.height, 2 * 1.1, 1e-12);
}

TEST(FrameSceneBuilderTest, BoxBecomesFourCapsulesOutsideTheCorners) {
    scene::Scene s = boxed_scene();
    s.walls[0].thickness = 0.2;
    FrameSceneBuilder builder(s);
    const render::FrameScene& frame = builder.build({});
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
    scene::Disc d;
    d.radius = 0.5;
    d.color = {255, 0, 0, 255};
    d.is_static = true;
    s.discs.push_back(d);
    FrameSceneBuilder builder(s);
    physics::DiscState state;
    state.position = {3, 4};
    state.angle = 1.5;
    const render::FrameScene& frame = builder.build({&state, 1});
    ASSERT_EQ(frame.discs.size(), 1u);
    EXPECT_EQ(frame.discs[0].x, 3.0f);
    EXPECT_EQ(frame.discs[0].y, 4.0f);
    EXPECT_EQ(frame.discs[0].angle, 1.5f);
    EXPECT_EQ(frame.discs[0].radius, 0.5f);
    EXPECT_EQ(frame.discs[0].fill.r, 1.0f);
    EXPECT_EQ(frame.discs[0].fill.g, 0.0f);
    EXPECT_TRUE(frame.discs[0].is_static);
}

}  // namespace
}  // namespace discreel::app

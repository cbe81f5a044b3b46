#include "stepper.hpp"

#include <gtest/gtest.h>

#include "build_world.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {
namespace {

// The loader rejects numbers that could overflow, so a broken-down world is built here from a
// scene that skipped it: the message must name the disc by its id and give the time.
TEST(FrameStepperTest, NamesTheDiscAndTimeWhenTheWorldBreaksDown) {
    scene::Scene scene;
    scene.physics.gravity = {0, 0};
    scene::Body runaway;
    runaway.id = "runaway";
    runaway.position = {0, 10};
    runaway.velocity = {8e307, 0};   // x overflows in step 1079 (see tests/physics)
    scene.bodies = {runaway};
    scene.video.fps = 60;
    scene.video.duration = 3;
    const Timeline timeline{scene.video.fps, scene.physics.rate, scene.video.frame_count()};
    physics::World world(build_world(scene));
    FrameStepper stepper(world, timeline, scene);
    EXPECT_TRUE(stepper.advance_to(134));   // 1072 steps: still finite
    const Status status = stepper.advance_to(179);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message,
              "the simulation broke down at t = 2.24792 s: disc 'runaway' has a position, "
              "velocity or spin that is no longer a finite number; the scene asks for more than "
              "the solver can represent (docs/physics.md, Limits)");
    EXPECT_EQ(world.step_count(), 1079) << "stepping stops at the failure";
}

}  // namespace
}  // namespace discreel::job

namespace discreel::job {
namespace {

scene::Scene one_body_scene(scene::Body body) {
    scene::Scene scene;
    scene.bodies = {std::move(body)};
    scene.video.fps = 60;
    scene.video.duration = 3;
    return scene;
}

// A body of another shape is a "body" in the message, as its author wrote it under bodies:.
TEST(FrameStepperTest, NamesABoxABody) {
    scene::Scene scene;
    scene.physics.gravity = {0, 0};
    scene::Body box;
    box.id = "crate";
    box.shape = *physics::box_shape(1, 1);
    box.radius = physics::bounding_radius(*box.shape);
    box.mass = 1;
    box.inertia = 1.0 / 6;
    box.position = {0, 10};
    box.velocity = {8e307, 0};
    scene = one_body_scene(box);
    scene.physics.gravity = {0, 0};
    const Timeline timeline{scene.video.fps, scene.physics.rate, scene.video.frame_count()};
    physics::World world(build_world(scene));
    FrameStepper stepper(world, timeline, scene);
    const Status status = stepper.advance_to(179);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message.rfind("the simulation broke down at t = ", 0), 0u);
    EXPECT_NE(status.error().message.find(" s: body 'crate' has a position"), std::string::npos)
        << status.error().message;
}

// Asked before every physics step: a frame of many steps stops within one.
TEST(FrameStepperTest, StopsBetweenPhysicsStepsWhenAsked) {
    scene::Body disc;
    disc.id = "a";
    disc.radius = 0.5;
    disc.mass = 1;
    disc.inertia = 0.125;
    scene::Scene scene = one_body_scene(disc);
    scene.physics.rate = 100000;
    scene.video.fps = 1;
    const Timeline timeline{scene.video.fps, scene.physics.rate, scene.video.frame_count()};
    physics::World world(build_world(scene));
    FrameStepper stepper(world, timeline, scene);
    int asked = 0;
    const Status status = stepper.advance_to(1, [&] { return ++asked > 250; });
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message, "cancelled; nothing was written");
    EXPECT_EQ(world.step_count(), 250);
}

// A body that leaves the box of walls it started in is said once, at the first frame it shows.
TEST(FrameStepperTest, ABodyThatLeavesItsBoxIsWarnedAboutOnce) {
    scene::Body disc;
    disc.id = "escapee";
    disc.radius = 0.1;
    disc.mass = 1;
    disc.inertia = 0.005;
    disc.position = {1, 1};
    scene::Scene scene = one_body_scene(disc);
    scene.physics.gravity = {0, 0};
    scene::Wall wall;
    wall.shape = scene::Wall::Shape::box;
    wall.a = {0, 0};
    wall.b = {2, 2};
    scene.walls = {wall};
    const Timeline timeline{scene.video.fps, scene.physics.rate, scene.video.frame_count()};
    // The world is built without the wall, as a solver that failed to hold the body would be.
    scene::Scene open = scene;
    open.walls.clear();
    open.bodies[0].velocity = {3, 0};
    physics::World world(build_world(open));
    FrameStepper stepper(world, timeline, scene);
    ASSERT_TRUE(stepper.advance_to(10));   // t = 1/6 s: at x = 1.5, inside
    EXPECT_TRUE(stepper.take_warnings().empty());
    ASSERT_TRUE(stepper.advance_to(30));   // x = 2.5: outside
    EXPECT_EQ(stepper.take_warnings(),
              std::vector<std::string>{"disc 'escapee' left the box of walls[0] by t = 0.5 s: "
                                       "the physics could not hold it there (docs/physics.md, "
                                       "Limits)"});
    ASSERT_TRUE(stepper.advance_to(60));
    EXPECT_TRUE(stepper.take_warnings().empty());
}

}  // namespace
}  // namespace discreel::job

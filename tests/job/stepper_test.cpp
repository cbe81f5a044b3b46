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
    scene::Disc runaway;
    runaway.id = "runaway";
    runaway.position = {0, 10};
    runaway.velocity = {8e307, 0};   // x overflows in step 1079 (see tests/physics)
    scene.discs = {runaway};
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

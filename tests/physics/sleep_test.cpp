// Sleeping islands of shaped bodies: a settled stack stops exactly and stays put; what reaches
// it (a falling ball, a flick, a respawn underneath) wakes it and moves as it would have had it
// never slept; a grabbed body pushes one ahead; waking raises no contact events of its own;
// `sleep = false` keeps bodies awake; bodies floating free never sleep.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::body;
using testing::Material;
using testing::run_for;

constexpr Material crate{.restitution = 0, .friction = 0.5};

bool at_rest(const BodyState& s) {
    return s.velocity.x == 0 && s.velocity.y == 0 && s.angular_velocity == 0;
}

// A stack of `count` unit boxes on a floor; a 0.3 m disc of 1 kg/m^2 above it at `ball_y` (or
// none), held there by a grab until `drop` s.
WorldDef stack(int count, double ball_y = 0, double drop = 0) {
    WorldDef def;
    def.walls.push_back(testing::box({-10, 0}, {10, 40}, crate));
    for (int i = 0; i < count; ++i) def.bodies.push_back(body(*box_shape(1, 1), {0, 0.5 + i}, 1, crate));
    if (ball_y > 0) {
        def.bodies.push_back(body(circle_shape(0.3), {0, ball_y}, 1, {.restitution = 0.5, .friction = 0.5}));
        ThrowDef hold;
        hold.body = def.bodies.size() - 1;
        hold.path = {{0, {0, ball_y}}, {drop, {0, ball_y}}};
        hold.release = Vec2{0, 0};
        def.throws = {hold};
    }
    return def;
}

TEST(Sleep, ASettledStackStopsExactlyAndStaysPut) {
    World world(stack(5));
    run_for(world, 2.0);
    std::vector<BodyState> settled(world.bodies().begin(), world.bodies().end());
    for (const BodyState& s : settled) EXPECT_TRUE(at_rest(s));
    run_for(world, 5.0);
    for (std::size_t i = 0; i < settled.size(); ++i) {
        EXPECT_EQ(world.bodies()[i].position.x, settled[i].position.x) << i;
        EXPECT_EQ(world.bodies()[i].position.y, settled[i].position.y) << i;
        EXPECT_EQ(world.bodies()[i].angle, settled[i].angle) << i;
    }
    // Asleep, the stack still touches itself and the floor: its contacts are counted.
    EXPECT_EQ(world.stats().contact_count, 5u);
}

TEST(Sleep, TurnedOffEveryBodyStaysAwake) {
    WorldDef def = stack(5);
    def.sleep = false;
    World world(def);
    run_for(world, 2.0);
    bool any_moving = false;
    for (const BodyState& s : world.bodies()) any_moving = any_moving || !at_rest(s);
    EXPECT_TRUE(any_moving);   // gravity and the contacts' impulses, cancelling to rounding
}

// A ball held 2 m above a 3-box stack until 2 s (the stack asleep by then) lands on it: the
// stack wakes, the ball bounces as it does on a stack that never slept, and the same contacts
// begin at the same steps (the ball's with the top box, then the boxes', which part for a
// moment under the blow): waking adds none.
TEST(Sleep, ABallLandingOnASleepingStackWakesItAndBouncesAsOnAnAwakeOne) {
    const double drop = 2.0;
    const std::size_t ball = 3;
    std::vector<double> highest;
    std::vector<std::vector<ContactEvent>> began;
    for (const bool sleep : {true, false}) {
        WorldDef def = stack(3, 5.3, drop);
        def.sleep = sleep;
        World world(def);
        run_for(world, drop);
        world.take_events();
        if (sleep) {
            EXPECT_TRUE(at_rest(world.bodies()[0]));
        }
        bool woke = false, bounced = false;
        double top = 0;
        std::vector<ContactEvent> events;
        for (int k = 0; k < world.rate(); ++k) {
            world.step();
            for (const ContactEvent& e : world.take_events()) events.push_back(e);
            const BodyState& b = world.bodies()[ball];
            woke = woke || !at_rest(world.bodies()[2]);
            if (b.velocity.y > 0) bounced = true;
            if (bounced) top = std::max(top, b.position.y);
        }
        EXPECT_TRUE(woke) << sleep;
        ASSERT_TRUE(bounced) << sleep;
        highest.push_back(top);
        began.push_back(events);
    }
    EXPECT_NEAR(highest[0], highest[1], 1e-3);
    ASSERT_EQ(began[0].size(), began[1].size());
    ASSERT_FALSE(began[0].empty());
    EXPECT_EQ(began[0][0].a, 2u);
    EXPECT_EQ(began[0][0].other, ball);
    for (std::size_t k = 0; k < began[0].size(); ++k) {
        EXPECT_EQ(began[0][k].t, began[1][k].t) << k;
        EXPECT_EQ(began[0][k].a, began[1][k].a) << k;
        EXPECT_EQ(began[0][k].other, began[1][k].other) << k;
    }
}

// A box asleep on the floor, flicked at 1 m/s, slides v^2 / (2 mu g) as an awake one does.
TEST(Sleep, AFlickedSleepingBoxSlidesAsCoulombSays) {
    const double mu = 0.5, v = 1.0, g = 9.81;
    WorldDef def;
    def.walls.push_back(testing::box({-10, 0}, {10, 40}, {.restitution = 0, .friction = mu}));
    def.bodies.push_back(body(*box_shape(1, 0.5), {0, 0.25}, 1, {.restitution = 0, .friction = mu}));
    ThrowDef flick;
    flick.at = 1.5;
    flick.velocity = Vec2{v, 0};
    def.throws = {flick};
    World world(def);
    run_for(world, 1.4);
    EXPECT_TRUE(at_rest(world.bodies()[0]));
    run_for(world, 1.1);
    EXPECT_NEAR(world.bodies()[0].position.x, v * v / (2 * mu * g), 2e-3);
}

// A box asleep on the floor; from 1.5 s another is carried by a grab along the floor into it at
// 1 m/s: the sleeping box wakes and is pushed ahead, as far as the carried one goes past first
// touch.
TEST(Sleep, AGrabbedBodyPushesASleepingOneAhead) {
    WorldDef def;
    def.walls.push_back(testing::box({-10, 0}, {10, 40}, crate));
    def.bodies.push_back(body(*box_shape(1, 1), {0, 0.5}, 1, crate));
    def.bodies.push_back(body(*box_shape(1, 1), {-3, 0.5}, 1, crate));
    ThrowDef grab;
    grab.body = 1;
    grab.path = {{1.5, {-3, 0.5}}, {4.5, {0, 0.5}}};   // first touch at 3.5 s, then 1 m on
    def.throws = {grab};
    World world(def);
    run_for(world, 1.4);
    EXPECT_TRUE(at_rest(world.bodies()[0]));
    run_for(world, 3.1);
    EXPECT_NEAR(world.bodies()[0].position.x, 1.0, 0.02);
}

// Two boxes stacked, asleep; the bottom one is replaced by a box far away: the top one falls.
TEST(Sleep, ARespawnUnderASleepingBoxWakesIt) {
    WorldDef def = stack(2);
    RespawnDef r;
    r.at = 2.0;
    r.first = 0;
    r.bodies = {body(*box_shape(1, 1), {5, 0.5}, 1, crate)};
    def.respawns = {r};
    World world(def);
    run_for(world, 1.99);
    EXPECT_TRUE(at_rest(world.bodies()[1]));
    run_for(world, 1.0);
    EXPECT_NEAR(world.bodies()[1].position.y, 0.5, 1e-3);
}

// Only what rests on something fixed sleeps. In zero gravity an elastic box glides at 5 mm/s
// (half the sleep speed) for 0.5 s into a box at rest, which leaves with its velocity: stopped
// for gliding slowly, the first box would halt with the momentum of both lost. A free pair
// touching, slower still, keeps drifting too.
TEST(Sleep, BodiesFloatingFreeKeepTheirMomentum) {
    for (const double speed : {0.005, 0.0005}) {
        SCOPED_TRACE(speed);
        WorldDef def;
        def.gravity = {0, 0};
        def.bodies = {body(*box_shape(0.5, 0.5), {0, 0}), body(*box_shape(0.5, 0.5), {0.5 + 0.5 * speed, 0})};
        def.bodies[0].velocity = {speed, 0};
        World world(def);
        run_for(world, 2.0);
        EXPECT_NEAR(world.bodies()[0].velocity.x, 0, 1e-9 * speed);
        EXPECT_NEAR(world.bodies()[1].velocity.x, speed, 1e-9 * speed);
    }
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies = {body(*box_shape(1, 1), {0, 0}), body(*box_shape(1, 1), {1, 0})};
    def.bodies[0].velocity = def.bodies[1].velocity = {0, 0.001};
    World world(def);
    run_for(world, 2.0);
    EXPECT_EQ(world.bodies()[0].velocity.y, 0.001);
    EXPECT_EQ(world.bodies()[1].velocity.y, 0.001);
}

// Near is not resting: a box gliding at 5 mm/s a centimetre above a wall in zero gravity is
// within the reach of its contact (the rows see it coming) but presses on nothing, and glides on.
TEST(Sleep, ABodyGlidingPastAWallKeepsItsMomentum) {
    WorldDef def;
    def.gravity = {0, 0};
    def.walls.push_back(testing::box({-10, -1}, {10, 0}, crate));
    def.bodies = {body(*box_shape(1, 1), {0, 0.51}, 1, crate)};
    def.bodies[0].velocity = {0.005, 0};
    World world(def);
    run_for(world, 2.0);
    EXPECT_EQ(world.bodies()[0].velocity.x, 0.005);
    EXPECT_NEAR(world.bodies()[0].position.x, 0.01, 1e-12);
}

}  // namespace
}  // namespace discreel::physics

// Joints against their analytic answers: pendulums, springs, ropes, chains, sliders, welds
// and Newton's cradle (docs/physics.md, "Joints").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::Material;

constexpr double g = 9.81;
constexpr double pi = std::numbers::pi;

WorldDef empty_world(Vec2 gravity = {0, -g}) {
    WorldDef def;
    def.gravity = gravity;
    return def;
}

JointDef joint(JointDef::Kind kind, std::optional<std::size_t> a, std::optional<std::size_t> b,
               Vec2 anchor_a, Vec2 anchor_b = {}) {
    JointDef j;
    j.kind = kind;
    j.a = a;
    j.b = b;
    j.anchor_a = anchor_a;
    j.anchor_b = kind == JointDef::Kind::distance ? anchor_b : anchor_a;
    return j;
}

double distance(const Vec2& p, const Vec2& q) { return std::hypot(p.x - q.x, p.y - q.y); }

// The times (s) at which f changes sign from negative to positive, interpolated within the
// step, over `seconds` of the world.
template <class F>
std::vector<double> upward_crossings(World& world, double seconds, F&& f) {
    std::vector<double> times;
    double before = f(world);
    double t_before = world.time();
    while (world.time() < seconds) {
        world.step();
        const double now = f(world);
        if (before < 0 && now >= 0) {
            times.push_back(t_before + (world.time() - t_before) * (-before / (now - before)));
        }
        before = now;
        t_before = world.time();
    }
    return times;
}

// A bob of radius r on a rod of length L from a fixed pivot, released at theta0 from rest.
WorldDef rod_pendulum(double length, double theta0, double r = 0.05) {
    WorldDef def = empty_world();
    const Vec2 pivot{0, 5};
    def.bodies.push_back(testing::disc(
        {pivot.x + length * std::sin(theta0), pivot.y - length * std::cos(theta0)}, {0, 0}, r, 1));
    JointDef rod = joint(JointDef::Kind::distance, std::nullopt, 0, pivot, def.bodies[0].position);
    def.joints.push_back(rod);
    return def;
}

// The period of a pendulum of small amplitude theta0 (radians) whose small-swing period is t0,
// to the fourth power of the amplitude.
double large_swing_period(double t0, double theta0) {
    const double s2 = theta0 * theta0;
    return t0 * (1 + s2 / 16 + 11 * s2 * s2 / 3072);
}

TEST(Joints, ARodPendulumSwingsWithThePeriodOfAPointMass) {
    // The rod is fixed at the bob's centre, so the bob does not turn: a point mass, T0 =
    // 2 pi sqrt(L / g).
    const double length = 2, theta0 = 5 * pi / 180;
    WorldDef def = rod_pendulum(length, theta0);
    World world(def);
    EXPECT_TRUE(world.manifold_solver());
    const auto crossings =
        upward_crossings(world, 30, [](const World& w) { return w.bodies()[0].velocity.x; });
    ASSERT_GE(crossings.size(), 11u);
    const double period = (crossings[10] - crossings[0]) / 10;
    const double expected = large_swing_period(2 * pi * std::sqrt(length / g), theta0);
    EXPECT_NEAR(period / expected, 1.0, 0.002) << period << " s against " << expected;
}

TEST(Joints, APinnedBarSwingsWithThePeriodOfItsMomentOfInertia) {
    // A 2 m x 0.1 m bar pinned 0.1 m from its end: T0 = 2 pi sqrt(I / (m g d)), I about the pin.
    WorldDef def = empty_world();
    const double w = 2.0, h = 0.1, theta0 = 5 * pi / 180;
    const double d = w / 2 - 0.1;   // pin to centroid
    const Vec2 pivot{0, 5};
    BodyDef bar = testing::body(box_shape(w, h).value(), {0, 0}, 10);
    bar.position = {pivot.x + d * std::sin(theta0), pivot.y - d * std::cos(theta0)};
    bar.angle = theta0 - pi / 2;
    def.bodies.push_back(bar);
    def.joints.push_back(joint(JointDef::Kind::revolute, std::nullopt, 0, pivot));
    World world(def);
    const double m = bar.mass;
    const double inertia = m * (w * w + h * h) / 12 + m * d * d;
    const auto crossings =
        upward_crossings(world, 40, [](const World& w) { return w.bodies()[0].angular_velocity; });
    ASSERT_GE(crossings.size(), 11u);
    const double period = (crossings[10] - crossings[0]) / 10;
    const double expected = large_swing_period(2 * pi * std::sqrt(inertia / (m * g * d)), theta0);
    EXPECT_NEAR(period / expected, 1.0, 0.002) << period << " s against " << expected;
}

TEST(Joints, APendulumKeepsItsEnergyForThirtySeconds) {
    WorldDef def = rod_pendulum(2, 5 * pi / 180);
    World world(def);
    const double e0 = world.energy();
    const double swing = 1 * g * 2 * (1 - std::cos(5 * pi / 180));   // J: its potential range
    double worst = 0;
    while (world.time() < 30) {
        world.step();
        worst = std::max(worst, std::abs(world.energy() - e0));
    }
    // Against the energy that swings between kinetic and potential (the whole energy's
    // zero is arbitrary).
    EXPECT_LT(worst / swing, 0.005) << worst << " J of " << swing;
}

TEST(Joints, APinnedAnchorsStayTogether) {
    WorldDef def = rod_pendulum(2, 60 * pi / 180);
    World world(def);
    double worst = 0;
    while (world.time() < 10) {
        world.step();
        const JointState& s = world.joints()[0];
        worst = std::max(worst, std::abs(distance(s.anchor_a, s.anchor_b) - 2));
    }
    EXPECT_LT(worst, 1e-4);
}

// A body on a spring of `frequency` (Hz) and damping ratio `zeta` from a fixed anchor, in no
// gravity, pulled 0.1 m along the spring.
WorldDef spring_world(double frequency, double zeta) {
    WorldDef def = empty_world({0, 0});
    def.bodies.push_back(testing::disc({1.1, 0}, {0, 0}, 0.1, 2));
    JointDef spring = joint(JointDef::Kind::distance, std::nullopt, 0, {0, 0}, {1.1, 0});
    spring.length = 1;
    spring.spring = SpringDef{frequency, zeta};
    def.joints.push_back(spring);
    return def;
}

TEST(Joints, AnUndampedSpringRingsAtItsFrequencyAndKeepsItsAmplitude) {
    World world(spring_world(2, 0));
    double lowest = 1.1;
    const auto crossings = upward_crossings(world, 10, [&](const World& w) {
        lowest = std::min(lowest, w.bodies()[0].position.x);
        return w.bodies()[0].velocity.x;
    });
    ASSERT_GE(crossings.size(), 19u);
    const double period = (crossings.back() - crossings.front()) /
                          static_cast<double>(crossings.size() - 1);
    EXPECT_NEAR(period * 2, 1.0, 0.005);
    EXPECT_NEAR(lowest, 0.9, 1e-3);   // swings through to the other side, undiminished
}

TEST(Joints, ADampedSpringDecaysAtItsDampingRate) {
    const double f = 2, zeta = 0.1, omega = 2 * pi * f;
    World world(spring_world(f, zeta));
    // Peaks of the stretch (velocity through zero downwards) against e^(-zeta omega t).
    std::vector<std::pair<double, double>> peaks;   // (t, stretch)
    double v_before = 0;
    while (world.time() < 3) {
        world.step();
        const BodyState& s = world.bodies()[0];
        if (v_before > 0 && s.velocity.x <= 0) peaks.emplace_back(world.time(), s.position.x - 1);
        v_before = s.velocity.x;
    }
    ASSERT_GE(peaks.size(), 4u);
    for (const auto& [t, stretch] : peaks) {
        const double expected = 0.1 * std::exp(-zeta * omega * t);
        EXPECT_NEAR(stretch / expected, 1.0, 0.02) << "at " << t << " s";
    }
}

TEST(Joints, ARopeNeverStretchesAndPullsNothingWhenSlack) {
    // A bob thrown up and sideways within its rope's reach flies free until the rope tightens.
    WorldDef def = empty_world();
    def.bodies.push_back(testing::disc({0, 4.5}, {1.5, 2}, 0.05, 1));
    JointDef rope = joint(JointDef::Kind::distance, std::nullopt, 0, {0, 5}, {0, 4.5});
    rope.length = 1;
    rope.rope = true;
    def.joints.push_back(rope);
    World world(def);
    bool taut = false;
    double longest = 0;
    while (world.time() < 5) {
        world.step();
        const BodyState& s = world.bodies()[0];
        const double t = world.time();
        const double reach = distance(s.position, {0, 5});
        longest = std::max(longest, reach);
        taut = taut || reach > 1 - 1e-3;
        if (!taut) {
            EXPECT_NEAR(s.position.x, 1.5 * t, 1e-9);
            EXPECT_NEAR(s.position.y, 4.5 + 2 * t - 0.5 * g * t * t, 1e-9);
        }
    }
    EXPECT_TRUE(taut);
    EXPECT_LT(longest, 1 + 1e-3);
}

// A chain of n capsules, each `link` m between its pins, laid out horizontally from a fixed
// pin at `top`.
WorldDef chain(int n, double link, Vec2 top) {
    WorldDef def = empty_world();
    const Shape capsule = capsule_shape(link, 0.05).value();
    for (int i = 0; i < n; ++i) {
        def.bodies.push_back(
            testing::body(capsule, {top.x + (i + 0.5) * link, top.y}, 20, Material{0.0, 0.3}));
        const Vec2 pin{top.x + i * link, top.y};
        def.joints.push_back(joint(JointDef::Kind::revolute,
                                   i == 0 ? std::nullopt : std::optional<std::size_t>(i - 1),
                                   static_cast<std::size_t>(i), pin));
    }
    return def;
}

TEST(Joints, ADroppedChainKeepsItsPinsTogetherAndNeverGainsEnergy) {
    World world(chain(20, 0.25, {0, 8}));
    const int per_frame = world.rate() / 60;
    double worst_gap = 0, worst_rise = 0;
    double before = world.energy();
    while (world.time() < 6) {
        for (int k = 0; k < per_frame; ++k) world.step();
        for (const JointState& s : world.joints()) {
            worst_gap = std::max(worst_gap, distance(s.anchor_a, s.anchor_b));
        }
        const double now = world.energy();
        worst_rise = std::max(worst_rise, now - before);
        before = now;
    }
    EXPECT_LT(worst_gap, 1e-3);
    EXPECT_LE(worst_rise, 1e-9);
}

TEST(Joints, JoinedBodiesPassThroughEachOtherUnlessTheJointSaysCollide) {
    for (const bool collide : {false, true}) {
        WorldDef def = empty_world({0, 0});
        def.bodies.push_back(testing::disc({0, 0}, {0, 0}, 0.5, 1));
        def.bodies.push_back(testing::disc({0.6, 0}, {0, 0}, 0.5, 1));
        JointDef rod = joint(JointDef::Kind::distance, 0, 1, {0, 0}, {0.6, 0});
        rod.rope = true;   // lets them part, never farther than 0.6 m... apart
        rod.length = 2;
        rod.collide = collide;
        def.joints.push_back(rod);
        World world(def);
        for (int i = 0; i < 480; ++i) world.step();
        const double apart = distance(world.bodies()[0].position, world.bodies()[1].position);
        if (collide) {
            EXPECT_GT(apart, 1.0 - 1e-3);
        } else {
            EXPECT_DOUBLE_EQ(apart, 0.6);
        }
    }
}

TEST(Joints, ARevoluteMotorTurnsAtItsSpeedAndLimitsHold) {
    WorldDef def = empty_world();
    def.bodies.push_back(testing::body(box_shape(2, 0.2).value(), {0, 5}, 5));
    JointDef pin = joint(JointDef::Kind::revolute, std::nullopt, 0, {0, 5});
    pin.motor = JointDef::Motor{3, 1000};
    def.joints.push_back(pin);
    World motor(def);
    while (motor.time() < 2) motor.step();
    EXPECT_NEAR(motor.bodies()[0].angular_velocity, 3, 1e-9);
    EXPECT_NEAR(motor.bodies()[0].angle, 3 * motor.time(), 0.01);

    // Off centre and limited to +-0.3 rad, released level: it stops at the lower limit.
    WorldDef limited = empty_world();
    limited.bodies.push_back(testing::body(box_shape(2, 0.2).value(), {1, 5}, 5));
    JointDef hinge = joint(JointDef::Kind::revolute, std::nullopt, 0, {0, 5});
    hinge.limits = std::array<double, 2>{-0.3, 0.3};
    limited.joints.push_back(hinge);
    World world(limited);
    double lowest = 0;
    while (world.time() < 3) {
        world.step();
        lowest = std::min(lowest, world.bodies()[0].angle);
    }
    EXPECT_GT(lowest, -0.3 - 1e-3);
    EXPECT_NEAR(world.bodies()[0].angle, -0.3, 1e-3);
}

TEST(Joints, APrismaticMotorLiftsAtItsSpeedAndStallsAtItsForce) {
    for (const double max_force : {100.0, 5.0}) {
        WorldDef def = empty_world();
        def.bodies.push_back(testing::body(box_shape(0.5, 0.5).value(), {0, 1}, 4));   // 1 kg
        JointDef slider = joint(JointDef::Kind::prismatic, std::nullopt, 0, {0, 1});
        slider.axis = {0, 1};
        slider.motor = JointDef::Motor{0.5, max_force};
        def.joints.push_back(slider);
        World world(def);
        while (world.time() < 1) world.step();
        const BodyState& s = world.bodies()[0];
        EXPECT_NEAR(s.position.x, 0, 1e-6);
        EXPECT_NEAR(s.angle, 0, 1e-6);
        if (max_force > g) {
            EXPECT_NEAR(s.velocity.y / 0.5, 1, 0.005);
        } else {
            // Stalled: the motor's 5 N against the weight, (5 - m g) / m down.
            EXPECT_NEAR(s.velocity.y / ((5 - g) * world.time()), 1, 0.005);
        }
    }
}

TEST(Joints, AWeldedCantileverSagsUnderTwoMillimetres) {
    WorldDef def = empty_world();
    const double w = 0.5;
    for (int i = 0; i < 5; ++i) {
        def.bodies.push_back(testing::body(box_shape(w, 0.2).value(), {(i + 0.5) * w, 5}, 10));
        def.joints.push_back(joint(JointDef::Kind::weld,
                                   i == 0 ? std::nullopt : std::optional<std::size_t>(i - 1),
                                   static_cast<std::size_t>(i), {i * w, 5}));
    }
    World world(def);
    while (world.time() < 3) world.step();
    EXPECT_GT(world.bodies()[4].position.y, 5 - 2e-3);
}

TEST(Joints, AHeavyArmCarriesALightBob) {
    // A 1 000 kg arm pinned to the world, released level, a 1 kg bob on a rod from its end: a
    // double pendulum swinging through its whole range.
    WorldDef def = empty_world();
    BodyDef arm = testing::body(box_shape(2, 0.1).value(), {1, 5}, 1);
    arm.mass = 1000;
    def.bodies.push_back(arm);
    def.bodies.push_back(testing::disc({2, 4}, {0, 0}, 0.1, 1));
    def.joints.push_back(joint(JointDef::Kind::revolute, std::nullopt, 0, {0, 5}));
    def.joints.push_back(joint(JointDef::Kind::distance, 0, 1, {2, 5}, {2, 4}));
    World world(def);
    const double swing = 1000 * g * 1;   // J: the arm's centre falls 1 m to the bottom
    double before = world.energy();
    const double e0 = before;
    double worst = 0, rise = 0;
    while (world.time() < 5) {
        world.step();
        const auto joints = world.joints();
        worst = std::max({worst, distance(joints[0].anchor_a, joints[0].anchor_b),
                          std::abs(distance(joints[1].anchor_a, joints[1].anchor_b) - 1)});
        rise = std::max(rise, world.energy() - before);
        before = world.energy();
    }
    EXPECT_LT(worst, 1e-3);
    EXPECT_LE(rise, 1e-9 * std::abs(e0));
    // The step's integration loses a little of a fast swing, never gains: measured 3.8 % of
    // the swing in 5 s (docs/physics.md, "Joints").
    EXPECT_GT(world.energy() - e0, -0.05 * swing);
}

TEST(Joints, NewtonsCradlePassesTheFirstBallsSpeedToTheLast) {
    // Five elastic balls on 1 m rods, touching; the first released from 30 degrees.
    WorldDef def = empty_world();
    const double r = 0.1, length = 1, theta0 = pi / 6;
    for (int i = 0; i < 5; ++i) {
        const Vec2 pivot{2 * r * i, 3};
        Vec2 at{pivot.x, pivot.y - length};
        if (i == 0) at = {pivot.x - length * std::sin(theta0), pivot.y - length * std::cos(theta0)};
        def.bodies.push_back(testing::disc(at, {0, 0}, r, 1));
        def.joints.push_back(joint(JointDef::Kind::distance, std::nullopt,
                                   static_cast<std::size_t>(i), pivot, at));
    }
    World world(def);
    const double arrive = std::sqrt(2 * g * length * (1 - std::cos(theta0)));
    // Until just after the first impact: the fifth ball moves off.
    while (world.time() < 2 && world.bodies()[4].velocity.x < 0.5 * arrive) world.step();
    for (int i = 0; i < 10; ++i) world.step();
    const auto speed = [&](int i) {
        const Vec2 v = world.bodies()[static_cast<std::size_t>(i)].velocity;
        return std::hypot(v.x, v.y);
    };
    EXPECT_NEAR(speed(4) / arrive, 1, 0.02);
    for (int i = 0; i < 4; ++i) EXPECT_LT(speed(i) / arrive, 0.02) << "ball " << i;
}

TEST(Joints, SameSceneSameBits) {
    const auto run = [] {
        World world(chain(10, 0.3, {0, 6}));
        while (world.time() < 2) world.step();
        std::vector<double> out;
        for (const BodyState& s : world.bodies()) {
            out.insert(out.end(), {s.position.x, s.position.y, s.angle});
        }
        return out;
    };
    EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace discreel::physics

namespace discreel::physics {
namespace {

// A kinematic body of this shape (any density: its mass does not matter) at `position`.
BodyDef kinematic_body(const Shape& shape, Vec2 position, KinematicDef motion) {
    BodyDef d = testing::body(shape, position, 1.0, testing::Material{0.0, 0.5});
    d.kinematic = std::move(motion);
    return d;
}

TEST(Kinematic, AWindmillTurnsExactlyAndKnocksADiscOffIt) {
    WorldDef def = empty_world();
    KinematicDef turning;
    turning.angular_velocity = 3;
    def.bodies.push_back(kinematic_body(box_shape(3, 0.2).value(), {5, 5}, turning));
    def.bodies.push_back(testing::disc({6, 5.35}, {0, 0}, 0.25, 1, testing::Material{0.0, 0.5}));
    World world(def);
    double fastest = 0;
    while (world.time() < 2) {
        world.step();
        const BodyState& sail = world.bodies()[0];
        ASSERT_NEAR(sail.angle, 3 * world.time(), 1e-9);
        ASSERT_EQ(sail.position.x, 5);
        ASSERT_EQ(sail.position.y, 5);
        const Vec2 v = world.bodies()[1].velocity;
        fastest = std::max(fastest, std::hypot(v.x, v.y));
    }
    // Struck by the sail's far half, faster than 3 rad/s x its 1 m from the pin.
    EXPECT_GT(fastest, 3.0);
    EXPECT_GT(std::abs(world.bodies()[1].position.x - 5), 1.6);   // beyond the sail's reach
}

TEST(Kinematic, APlatformCarriesWhatRestsOnIt) {
    WorldDef def = empty_world();
    KinematicDef gliding;
    gliding.velocity = {1.5, 0};
    def.bodies.push_back(kinematic_body(box_shape(4, 0.2).value(), {0, 1}, gliding));
    def.bodies.push_back(testing::body(box_shape(0.4, 0.4).value(), {0, 1.3}, 1.0,
                                       testing::Material{0.0, 0.8}));
    World world(def);
    while (world.time() < 2) world.step();
    EXPECT_NEAR(world.bodies()[0].position.x, 3, 1e-12);
    EXPECT_NEAR(world.bodies()[1].velocity.x, 1.5, 1e-6);   // riding along by friction
    EXPECT_NEAR(world.bodies()[1].position.y, 1.3, 1e-3);
}

TEST(Kinematic, APathIsFollowedThroughItsPosesAndLoops) {
    WorldDef def = empty_world({0, 0});
    KinematicDef path;
    path.path = {{0, {0, 5}, 0}, {2, {8, 5}, 1.57}, {4, {0, 5}, 0}};
    path.loop = true;
    def.bodies.push_back(kinematic_body(box_shape(2, 0.2).value(), {0, 5}, path));
    World world(def);
    const auto at = [&](double t) {
        while (world.time() < t - 1e-12) world.step();
        return world.bodies()[0];
    };
    EXPECT_NEAR(at(1).position.x, 4, 1e-9);
    EXPECT_NEAR(at(2).angle, 1.57, 1e-9);
    EXPECT_NEAR(at(3).position.x, 4, 1e-9);
    EXPECT_NEAR(at(5).position.x, 4, 1e-9);   // the second lap
    EXPECT_NEAR(at(5).velocity.x, 4, 1e-9);
}

TEST(Kinematic, ALoopThatJumpsBackNeverSweepsAtTheJumpsSpeed) {
    // From x = 2 to 6 in a second, then back to 2 for the next lap: the step of the jump keeps
    // the lap's 4 m/s and puts the body at the lap's start at its end.
    WorldDef def = empty_world({0, 0});
    KinematicDef path;
    path.path = {{0, {2, 5}, 0}, {1, {6, 5}, 0}};
    path.loop = true;
    def.bodies.push_back(kinematic_body(box_shape(1, 0.2).value(), {2, 5}, path));
    World world(def);
    double fastest = 0;
    while (world.time() < 2.5) {
        world.step();
        fastest = std::max(fastest, std::abs(world.bodies()[0].velocity.x));
        const double lap = world.time() - std::floor(world.time());
        ASSERT_NEAR(world.bodies()[0].position.x, 2 + 4 * lap, 1e-9) << world.time();
    }
    EXPECT_NEAR(fastest, 4, 1e-9);
}

TEST(Kinematic, AKinematicDiscAmongDiscsMovesExactlyAndPushes) {
    // Plain discs only: the disc solver holds it as it holds a grabbed disc.
    WorldDef def = empty_world({0, 0});
    BodyDef pusher = testing::disc({0, 0}, {0, 0}, 0.5, 1);
    pusher.kinematic = KinematicDef{};
    pusher.kinematic->velocity = {2, 0};
    def.bodies.push_back(pusher);
    def.bodies.push_back(testing::disc({3, 0}, {0, 0}, 0.5, 1));
    World world(def);
    EXPECT_FALSE(world.manifold_solver());
    while (world.time() < 2) world.step();
    EXPECT_NEAR(world.bodies()[0].position.x, 4, 1e-9);
    EXPECT_NEAR(world.bodies()[0].velocity.x, 2, 1e-9);
    // Elastic: struck by an infinitely heavy body at 2 m/s, it leaves at 4 m/s.
    EXPECT_NEAR(world.bodies()[1].velocity.x, 4, 1e-6);
}

}  // namespace
}  // namespace discreel::physics

namespace discreel::physics {
namespace {

TEST(Filters, DiscsWhoseCategoriesExcludeEachOtherPassThroughAndStillMeetWalls) {
    WorldDef def = empty_world({0, 0});
    def.walls.push_back(testing::box({-5, -5}, {5, 5}));
    BodyDef ghost = testing::disc({-2, 0}, {2, 0}, 0.5, 1);
    ghost.category = 4;                 // "ghosts"
    ghost.collides = 2;                 // walls only
    def.bodies.push_back(ghost);
    def.bodies.push_back(testing::disc({2, 0}, {-2, 0}, 0.5, 1));   // meets everything
    World world(def);
    EXPECT_TRUE(world.manifold_solver());
    while (world.time() < 1) world.step();
    // They crossed without touching: each 2 m on.
    EXPECT_NEAR(world.bodies()[0].position.x, 0, 1e-9);
    EXPECT_NEAR(world.bodies()[1].position.x, 0, 1e-9);
    EXPECT_TRUE(world.take_events().empty());
    while (world.time() < 4) world.step();
    // ... and bounced off the walls (reached at 3.25 s), elastic.
    EXPECT_NEAR(world.bodies()[0].velocity.x, -2, 1e-9);
    EXPECT_NEAR(world.bodies()[1].velocity.x, 2, 1e-9);
}

TEST(Sensors, ADiscFallingThroughASensorBeginsAndEndsWithinAStep) {
    // A disc of r = 0.2 dropped from rest at y = 5 through a static 1 m tall sensor from y = 2
    // to 3: it overlaps once its bottom passes 3 and until its top passes 2.
    WorldDef def = empty_world();
    BodyDef gate = testing::body(box_shape(2, 1).value(), {0, 2.5});
    gate.is_static = true;
    gate.sensor = true;
    def.bodies.push_back(gate);
    def.bodies.push_back(testing::disc({0, 5}, {0, 0}, 0.2, 1));
    World world(def);
    std::vector<ContactEvent> events;
    while (world.time() < 2) {
        world.step();
        for (const ContactEvent& e : world.take_events()) events.push_back(e);
    }
    ASSERT_EQ(events.size(), 2u);
    const double begin = std::sqrt(2 * (5 - 0.2 - 3) / g), end = std::sqrt(2 * (5 + 0.2 - 2) / g);
    EXPECT_EQ(events[0].kind, ContactEvent::Kind::begin);
    EXPECT_EQ(events[0].a, 0u);
    EXPECT_EQ(events[0].other, 1u);
    EXPECT_EQ(events[0].impulse, 0);
    EXPECT_NEAR(events[0].t, begin, 1.0 / world.rate());
    EXPECT_GE(events[0].t, begin);
    EXPECT_EQ(events[1].kind, ContactEvent::Kind::end);
    EXPECT_NEAR(events[1].t, end, 1.0 / world.rate());
    EXPECT_GE(events[1].t, end);
    // It pushed nothing: the disc fell freely through.
    EXPECT_NEAR(world.bodies()[1].velocity.y, -g * world.time(), 1e-9);
}

TEST(Sensors, AStaticSensorSeesAKinematicBodyPassThrough) {
    // A 0.4 m box carried at 2 m/s along y = 2.5 from x = -3 through a static sensor 2 m wide
    // at the origin: it overlaps from x = -1.2 to x = 1.2, t = 0.9 s to 2.1 s.
    WorldDef def = empty_world();
    BodyDef gate = testing::body(box_shape(2, 1).value(), {0, 2.5});
    gate.is_static = true;
    gate.sensor = true;
    def.bodies.push_back(gate);
    BodyDef carried = testing::body(box_shape(0.4, 0.4).value(), {-3, 2.5});
    KinematicDef motion;
    motion.velocity = {2, 0};
    carried.kinematic = motion;
    def.bodies.push_back(carried);
    World world(def);
    std::vector<ContactEvent> events;
    while (world.time() < 3) {
        world.step();
        for (const ContactEvent& e : world.take_events()) events.push_back(e);
    }
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].kind, ContactEvent::Kind::begin);
    EXPECT_EQ(events[0].a, 0u);
    EXPECT_EQ(events[0].other, 1u);
    EXPECT_GE(events[0].t, 0.9);
    EXPECT_NEAR(events[0].t, 0.9, 1.0 / world.rate());
    EXPECT_EQ(events[1].kind, ContactEvent::Kind::end);
    EXPECT_GE(events[1].t, 2.1);
    EXPECT_NEAR(events[1].t, 2.1, 1.0 / world.rate());
    // Carried exactly: the sensor pushed nothing.
    EXPECT_NEAR(world.bodies()[1].position.x, -3 + 2 * world.time(), 1e-9);
}

}  // namespace
}  // namespace discreel::physics

// Bodies of every shape in the world, against Newton: a box at rest stays put, a flat landing
// rebounds to e^2 h without spin, a box on an incline slides at g (sin - mu cos) or sticks,
// spinning polygons collide conserving momentum and angular momentum, a disc hits a box as the
// 1-D formula says, a stack and a pyramid stand, a box bullet stays inside a thin wall, and
// respawned bodies replace the old ones.
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::body;
using testing::disc;
using testing::box;
using testing::Material;
using testing::run_for;

Shape box_of(double w, double h) { return *box_shape(w, h); }

// A world with a floor (a box wall whose inside starts at y = 0).
WorldDef on_floor(Material floor = {.restitution = 0.0, .friction = 0.5}) {
    WorldDef def;
    def.walls.push_back(box({-20, 0}, {20, 40}, floor));
    return def;
}

TEST(Bodies, ABoxAtRestStaysWithinATenthOfAMillimetreFor10s) {
    WorldDef def = on_floor();
    def.bodies.push_back(body(box_of(1, 0.5), {0.3, 0.25}, 1, {.restitution = 0.5, .friction = 0.5}));
    World world(def);
    double farthest = 0;
    for (int k = 0; k < 10 * world.rate(); ++k) {
        world.step();
        const Vec2 p = world.bodies()[0].position;
        farthest = std::max(farthest, std::hypot(p.x - 0.3, p.y - 0.25));
    }
    EXPECT_LT(farthest, 1e-4);
    EXPECT_LT(std::abs(world.bodies()[0].angle), 1e-6);
}

TEST(Bodies, AFlatLandingReboundsToESquaredHWithoutSpin) {
    const double h = 1.0, e = 0.5;
    WorldDef def = on_floor({.restitution = e, .friction = 0.5});
    def.bodies.push_back(body(box_of(1, 0.5), {0.3, 0.25 + h}, 1, {.restitution = e, .friction = 0.5}));
    World world(def);
    const std::optional<double> top = testing::rebound_height(world, 0, 0.25, [](const BodyState& s) {
        EXPECT_LT(std::abs(s.angular_velocity), 1e-9);
    });
    ASSERT_TRUE(top);
    EXPECT_NEAR(*top, e * e * h, 0.02 * e * e * h);   // 2 %: the step's discretisation
}

// A static box tilted 20 degrees is the incline; mu = 0.2 < tan 20 slides at
// a = g (sin - mu cos), mu = 0.5 > tan 20 sticks.
TEST(Bodies, ABoxOnAnInclineSlidesOrSticksAsCoulombSays) {
    const double theta = 20 * std::numbers::pi / 180, g = 9.81;
    for (const double mu : {0.2, 0.5}) {
        WorldDef def;
        BodyDef slope = body(box_of(40, 2), {0, 0}, 1, {.restitution = 0, .friction = mu});
        slope.angle = theta;
        slope.is_static = true;
        def.bodies.push_back(slope);
        const Vec2 along{std::cos(theta), std::sin(theta)}, up{-std::sin(theta), std::cos(theta)};
        BodyDef crate = body(box_of(0.5, 0.5), {along.x + up.x * 1.25, along.y + up.y * 1.25}, 1,
                             {.restitution = 0, .friction = mu});
        crate.angle = theta;
        def.bodies.push_back(crate);
        World world(def);
        run_for(world, 0.1);   // settled on the face
        const auto distance = [&] {
            const Vec2 p = world.bodies()[1].position;
            return p.x * along.x + p.y * along.y;
        };
        const double s0 = distance();
        const Vec2 v0 = world.bodies()[1].velocity;
        const double u0 = v0.x * along.x + v0.y * along.y;
        run_for(world, 1.0);
        const double travelled = distance() - s0;
        if (mu < std::tan(theta)) {
            const double a = -g * (std::sin(theta) - mu * std::cos(theta));   // down the slope
            EXPECT_NEAR(travelled, u0 * 1.0 + 0.5 * a, 0.01 * std::abs(0.5 * a)) << mu;
        } else {
            EXPECT_LT(std::abs(travelled), 1e-4) << mu;
        }
        EXPECT_NEAR(world.bodies()[1].angle, theta, 1e-3) << mu;   // slides flat, no tumbling
    }
}

double kinetic(const World& world, const WorldDef& def) {
    double e = 0;
    for (std::size_t i = 0; i < def.bodies.size(); ++i) {
        const BodyState& s = world.bodies()[i];
        e += 0.5 * def.bodies[i].mass * (s.velocity.x * s.velocity.x + s.velocity.y * s.velocity.y) +
             0.5 * inertia_of(def.bodies[i]) * s.angular_velocity * s.angular_velocity;
    }
    return e;
}

// Elastic, frictionless and without gravity: linear and angular momentum (about the origin)
// are conserved to rounding, kinetic energy to 1 %.
TEST(Bodies, ElasticSpinningPolygonsConserveMomentumAndEnergy) {
    WorldDef def;
    def.gravity = {0, 0};
    const std::vector<Vec2> hexagon{{0.4, 0}, {0.2, 0.35}, {-0.2, 0.35}, {-0.4, 0}, {-0.2, -0.35}, {0.2, -0.35}};
    BodyDef a = body(polygon_shape(hexagon)->shape, {0, 0.1}, 2);
    a.velocity = {3, 0};
    a.angular_velocity = 5;
    BodyDef b = body(box_of(0.6, 0.4), {2, -0.1}, 1);
    b.velocity = {-2, 0.5};
    b.angular_velocity = -3;
    def.bodies = {a, b};
    const auto momenta = [&](const World& w) {
        std::array<double, 3> m{0, 0, 0};   // px, py, L
        for (std::size_t i = 0; i < 2; ++i) {
            const BodyState& s = w.bodies()[i];
            const double mass = def.bodies[i].mass;
            m[0] += mass * s.velocity.x;
            m[1] += mass * s.velocity.y;
            m[2] += mass * (s.position.x * s.velocity.y - s.position.y * s.velocity.x) +
                    inertia_of(def.bodies[i]) * s.angular_velocity;
        }
        return m;
    };
    World world(def);
    const auto before = momenta(world);
    const double e0 = kinetic(world, def);
    std::size_t contacts = 0;
    double overlap = 0;
    for (int k = 0; k < world.rate(); ++k) {
        world.step();
        contacts += world.take_events().size();
        overlap = std::max(overlap, world.stats().max_overlap);
    }
    EXPECT_LT(overlap, 5e-4);   // never pushed apart (that would move them without momentum)
    EXPECT_GE(contacts, 1u);   // they did collide
    const auto after = momenta(world);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(after[k], before[k], 1e-9) << k;
    EXPECT_NEAR(kinetic(world, def), e0, 0.01 * e0);
}

// A disc hits a box squarely along x: the 1-D formula for restitution e gives both velocities.
TEST(Bodies, ADiscHitsABoxHeadOnAsTheOneDimensionalFormulaSays) {
    const double e = 0.6, m1 = 1.0, v1 = 4.0;
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies.push_back(testing::disc({0, 0}, {v1, 0}, 0.2, m1, {.restitution = e, .friction = 0.3}));
    BodyDef crate = body(box_of(0.5, 0.5), {1, 0}, 8, {.restitution = e, .friction = 0.3});
    def.bodies.push_back(crate);
    const double m2 = crate.mass;
    World world(def);
    run_for(world, 0.5);
    const double u1 = (m1 - e * m2) * v1 / (m1 + m2), u2 = (1 + e) * m1 * v1 / (m1 + m2);
    EXPECT_NEAR(world.bodies()[0].velocity.x, u1, 1e-9);
    EXPECT_NEAR(world.bodies()[1].velocity.x, u2, 1e-9);
    EXPECT_NEAR(world.bodies()[1].velocity.y, 0, 1e-12);
    EXPECT_NEAR(world.bodies()[1].angular_velocity, 0, 1e-9);
}

// Two 0.5 m boxes flying at each other corner first along their diagonal at 5 m/s each (1 cm
// a step: slow, so their contact is the speculative one), e = 1, no friction: the corners meet
// and the boxes come back along the diagonal at the same speeds, never overlapping by more
// than the slop. (When the corners' faces did not overlap sideways the pair got no contact
// and the boxes slid a step's travel into each other before their faces caught.)
TEST(Bodies, BoxesMeetingCornerToCornerBounceBackAlongTheDiagonal) {
    const double v = 5, side = 0.5;
    WorldDef def;
    def.gravity = {0, 0};
    const double u = v * std::sqrt(0.5);
    BodyDef a = body(box_of(side, side), {-1, -1}, 1, {.restitution = 1, .friction = 0});
    a.velocity = {u, u};
    BodyDef b = body(box_of(side, side), {1, 1}, 1, {.restitution = 1, .friction = 0});
    b.velocity = {-u, -u};
    def.bodies = {a, b};
    World world(def);
    double deepest = 0;
    for (int k = 0; k < world.rate() / 2; ++k) {
        world.step();
        deepest = std::max(deepest, world.stats().max_overlap);
    }
    EXPECT_LT(deepest, 5e-4);
    EXPECT_NEAR(world.bodies()[0].velocity.x, -u, 1e-6 * v);
    EXPECT_NEAR(world.bodies()[0].velocity.y, -u, 1e-6 * v);
    EXPECT_NEAR(world.bodies()[1].velocity.x, u, 1e-6 * v);
    EXPECT_NEAR(world.bodies()[0].angular_velocity, 0, 1e-6);
}

// The bars: stacks within 5 mm of their ideal heights and 2 mm sideways.
void expect_stands(const WorldDef& def, double seconds, std::size_t first) {
    World world(def);
    run_for(world, seconds);
    double sag = 0, drift = 0;
    for (std::size_t i = first; i < def.bodies.size(); ++i) {
        sag = std::max(sag, std::abs(world.bodies()[i].position.y - def.bodies[i].position.y));
        drift = std::max(drift, std::abs(world.bodies()[i].position.x - def.bodies[i].position.x));
    }
    EXPECT_LT(sag, 5e-3);
    EXPECT_LT(drift, 2e-3);
}

TEST(Bodies, AStackOfTwentyBoxesStands) {
    WorldDef def = on_floor();
    for (int i = 0; i < 20; ++i) {
        def.bodies.push_back(body(box_of(1, 1), {0, 0.5 + i}, 1, {.restitution = 0, .friction = 0.5}));
    }
    expect_stands(def, 5.0, 0);
}

TEST(Bodies, ATwentyRowPyramidStands) {
    WorldDef def = on_floor({.restitution = 0, .friction = 0.6});
    for (int row = 0; row < 20; ++row) {
        const int n = 20 - row;
        for (int i = 0; i < n; ++i) {
            def.bodies.push_back(body(box_of(1, 1), {i - (n - 1) / 2.0, 0.5 + row}, 1,
                                     {.restitution = 0, .friction = 0.6}));
        }
    }
    expect_stands(def, 2.0, 0);
}

// A 10 cm box at 300 m/s (62 cm per step) against a 2 cm wall: it bounces back and never
// reaches the far side.
TEST(Bodies, ABoxBulletStaysInsideAThinWall) {
    WorldDef def;
    def.gravity = {0, 0};
    def.walls.push_back(testing::segment({1, -1}, {1, 1}, 0.02, {.restitution = 0.5}));
    for (const double spin : {0.0, 40.0}) {
        BodyDef bullet = body(box_of(0.1, 0.1), {0, 0.05}, 1, {.restitution = 0.5});
        bullet.velocity = {300, 0};
        bullet.angular_velocity = spin;
        def.bodies = {bullet};
        World world(def);
        double farthest = -1;
        for (int k = 0; k < world.rate() / 10; ++k) {
            world.step();
            farthest = std::max(farthest, world.bodies()[0].position.x);
        }
        EXPECT_LT(farthest, 1 - 0.01 - 0.05 + 1e-3) << spin;   // its face never past the wall's
        EXPECT_LT(world.bodies()[0].velocity.x, 0) << spin;     // and it came back
    }
}

// The same bullet, elastic, between a box's wall and a 2 cm wall 2 m away for a second, at 62 cm
// per step: its centre never crosses either wall, and with no friction its kinetic energy
// (linear and spin) stays what it was (1e-6, rounding over the hits). Without spin it turns
// 158 times; spinning, hits on its corners trade speed for spin (149 m/s and 6 400 rad/s at
// the end), so it turns 90 times.
TEST(Bodies, ABoxBulletBouncesBetweenAWallAndAThinOneForASecond) {
    WorldDef def;
    def.gravity = {0, 0};
    const testing::Material elastic{.restitution = 1, .friction = 0};
    def.walls.push_back(testing::box({-1, -1}, {3, 1}, elastic));
    def.walls.push_back(testing::segment({1, -1}, {1, 1}, 0.02, elastic));
    for (const double spin : {0.0, 40.0}) {
        BodyDef bullet = body(box_of(0.1, 0.1), {0, 0.05}, 1, elastic);
        bullet.velocity = {300, 0};
        bullet.angular_velocity = spin;
        def.bodies = {bullet};
        World world(def);
        const double start = world.energy();
        double nearest = 10, farthest = -10;
        int turns = 0;
        double last_vx = 300;
        for (int k = 0; k < world.rate(); ++k) {
            world.step();
            const BodyState& s = world.bodies()[0];
            nearest = std::min(nearest, s.position.x);
            farthest = std::max(farthest, s.position.x);
            if ((s.velocity.x > 0) != (last_vx > 0)) ++turns;
            last_vx = s.velocity.x;
        }
        EXPECT_GT(nearest, -1) << spin;
        EXPECT_LT(farthest, 1 - 0.01) << spin;
        EXPECT_GT(turns, spin == 0 ? 150 : 80) << spin;
        EXPECT_NEAR(world.energy(), start, 1e-6 * start) << spin;
    }
}

// One event per pair of bodies, whatever the number of points: a box landing flat touches
// the floor at two points and gives one row, with both points' impulse.
TEST(Bodies, ALandingIsOneEventWithTheTotalImpulse) {
    WorldDef def = on_floor({.restitution = 0.5, .friction = 0.5});
    def.bodies.push_back(body(box_of(1, 0.5), {0, 0.5}, 1, {.restitution = 0.5, .friction = 0.5}));
    World world(def);
    std::vector<ContactEvent> events;
    for (int k = 0; k < world.rate() / 4; ++k) {
        world.step();
        for (const ContactEvent& e : world.take_events()) events.push_back(e);
    }
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].a, 0u);
    EXPECT_EQ(events[0].other_kind, ContactEvent::Other::wall);
    EXPECT_EQ(events[0].other, 0u);
    // Landing from 0.25 m at sqrt(2 g h), leaving at e times that: the impulse m (1 + e) v.
    const double v = std::sqrt(2 * 9.81 * 0.25), m = def.bodies[0].mass;
    EXPECT_NEAR(events[0].impulse, m * 1.5 * v, 0.03 * m * 1.5 * v);
}

TEST(Bodies, ARespawnReplacesTheBodiesAtItsTime) {
    WorldDef def = on_floor();
    def.bodies.push_back(body(box_of(0.5, 0.5), {0, 2}, 1));
    def.bodies.push_back(body(box_of(0.5, 0.5), {2, 2}, 1));
    RespawnDef r;
    r.at = 0.5;
    r.first = 1;
    r.bodies = {body(*capsule_shape(0.6, 0.1), {5, 3}, 1)};
    def.respawns = {r};
    World world(def);
    run_for(world, 0.5);
    EXPECT_EQ(world.respawns_applied(), 0u);
    EXPECT_LT(world.bodies()[1].position.y, 1.0);   // fallen
    world.step();
    EXPECT_EQ(world.respawns_applied(), 1u);
    EXPECT_NEAR(world.bodies()[1].position.x, 5, 1e-12);
    // The step's fall along the exact parabola: g dt^2 / 2.
    EXPECT_NEAR(world.bodies()[1].position.y, 3 - 0.5 * 9.81 / 480 / 480, 1e-12);
}

// Discs respawned as discs stay with the disc solver: the new disc flies its exact parabola from
// where it appears, lands and rests; the disc its predecessor stood on is not pushed by it any
// more, and the new disc's landing is a contact that begins.
TEST(Bodies, ARespawnOfDiscsKeepsTheDiscSolver) {
    WorldDef def = on_floor();
    const Material dead{.restitution = 0, .friction = 0.5};
    def.bodies.push_back(disc({0, 0.5}, {0, 0}, 0.5, 1, dead));
    def.bodies.push_back(disc({0, 1.5}, {0, 0}, 0.5, 1, dead));
    RespawnDef r;
    r.at = 0.5;
    r.first = 1;
    r.bodies = {disc({5, 3}, {0, 0}, 0.25, 2, dead)};
    def.respawns = {r};
    World world(def);
    EXPECT_FALSE(world.manifold_solver());
    run_for(world, 0.5);
    (void)world.take_events();
    EXPECT_EQ(world.respawns_applied(), 0u);
    world.step();
    EXPECT_EQ(world.respawns_applied(), 1u);
    const double dt = 1.0 / world.rate();
    EXPECT_EQ(world.bodies()[1].position.x, 5);
    EXPECT_NEAR(world.bodies()[1].position.y, 3 - 0.5 * 9.81 * dt * dt, 1e-12);
    std::vector<ContactEvent> events;
    for (int k = 0; k < 2 * world.rate(); ++k) {
        world.step();
        for (const ContactEvent& e : world.take_events()) events.push_back(e);
    }
    EXPECT_NEAR(world.bodies()[1].position.y, 0.25, 1e-3);
    EXPECT_NEAR(world.bodies()[0].position.y, 0.5, 1e-3);
    EXPECT_NEAR(world.bodies()[0].position.x, 0, 1e-9);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].a, 1u);
    EXPECT_EQ(events[0].other_kind, ContactEvent::Other::wall);
    // Falling 2.75 m to land: sqrt(2 g h) = 7.3 m/s after about 0.75 s.
    EXPECT_NEAR(events[0].t, 0.5 + std::sqrt(2 * 2.75 / 9.81), 0.01);
}

// A disc respawned in place of a much larger one bounces as a disc of its own size: whether an
// approach is timed as an impact depends on the radius (docs/physics.md, "Impacts"), and an
// isolated elastic bounce that is timed returns to its drop height to rounding.
TEST(Bodies, ARespawnedDiscBouncesAsOneOfItsOwnSize) {
    // Landing at 0.6 m/s: faster than a 0.1 m disc's settle speed (0.31 m/s), slower than a
    // 2 m disc's (1.4 m/s). Ten drops, so that some substep starts within the touching gap.
    const double r = 0.1;
    for (int n = 0; n < 10; ++n) {
        const double drop = 0.6 * 0.6 / (2 * 9.81) + 1.25e-4 * n;
        WorldDef def = on_floor({.restitution = 1, .friction = 0});
        const Material elastic{.restitution = 1, .friction = 0};
        def.bodies.push_back(disc({0, 2}, {0, 0}, 2, 1, elastic));
        RespawnDef respawn;
        respawn.at = 0.1;   // after the big disc has stepped
        respawn.first = 0;
        respawn.bodies = {disc({0, r + drop}, {0, 0}, r, 1, elastic)};
        def.respawns = {respawn};
        World world(def);
        ASSERT_FALSE(world.manifold_solver());
        bool bounced = false;
        for (int k = 0; k < world.rate() && !bounced; ++k) {
            world.step();
            const BodyState& s = world.bodies()[0];
            if (world.respawns_applied() == 1 && s.velocity.y > 0 && s.position.y > r) {
                bounced = true;
                const double apex = s.position.y + s.velocity.y * s.velocity.y / (2 * 9.81) - r;
                EXPECT_NEAR(apex, drop, 1e-9 * drop) << "drop " << drop;
            }
        }
        EXPECT_TRUE(bounced) << "drop " << drop;
    }
}

TEST(Bodies, ThrowsMoveBodiesLikeDiscs) {
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies.push_back(body(box_of(0.5, 0.5), {0, 0}, 1));
    def.bodies.push_back(body(box_of(0.5, 0.5), {5, 0}, 1));
    ThrowDef flick;
    flick.body = 0;
    flick.at = 0.25;
    flick.velocity = Vec2{2, 1};
    ThrowDef grab;
    grab.body = 1;
    grab.path = {{0.5, {6, 1}}, {1.0, {7, 1}}};
    def.throws = {flick, grab};
    World world(def);
    run_for(world, 0.5);
    EXPECT_NEAR(world.bodies()[0].position.x, 0.5, 1e-9);
    EXPECT_NEAR(world.bodies()[1].position.x, 6, 1e-9);
    EXPECT_NEAR(world.bodies()[1].position.y, 1, 1e-9);
    run_for(world, 1.0);
    EXPECT_NEAR(world.bodies()[1].velocity.x, 2, 1e-9);   // released with the path's velocity
}

}  // namespace
}  // namespace discreel::physics

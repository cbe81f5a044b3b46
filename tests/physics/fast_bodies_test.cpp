// Fast against fast for bodies of any shape: boxes meet at their time of impact, found by
// conservative advancement, whatever their speeds and however they cross, and move on for
// the rest of the step. Overlap is measured here by separating axes, independently of the
// solver's own statistics.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::body;

// How deep two squares of side `side` overlap (m): the least overlap of their projections on
// the four axes of their edges; 0 when apart.
double square_overlap(const BodyState& a, const BodyState& b, double side) {
    const double h = side / 2;
    double least = HUGE_VAL;
    for (const double angle : {a.angle, b.angle, a.angle + M_PI / 2, b.angle + M_PI / 2}) {
        const double ux = std::cos(angle), uy = std::sin(angle);
        const auto reach = [&](double phi) {
            return h * (std::abs(std::cos(phi - angle)) + std::abs(std::sin(phi - angle)));
        };
        const double apart = std::abs((b.position.x - a.position.x) * ux +
                                      (b.position.y - a.position.y) * uy);
        least = std::min(least, reach(a.angle) + reach(b.angle) - apart);
    }
    return std::max(0.0, least);
}

class BoxesHeadOn : public ::testing::TestWithParam<double> {};

// Two 10 cm boxes, 1.9 m apart, closing at 2 v with e = 1 and no friction: at 500 m/s each
// covers 21 half-widths per step. They meet inside a step at t* = 1.9 / 2v, swap velocities,
// never overlap, and are apart at the end by what they flew since t*: no time is lost (a
// bounce at the step's end would leave them short by up to 2 v dt, 2 m at 500 m/s). Tolerance:
// the surfaces are stopped up to 0.25 mm apart (body_impacts.cpp).
TEST_P(BoxesHeadOn, SwapVelocitiesAtTheirTimeOfImpact) {
    const double v = GetParam(), side = 0.1;
    WorldDef def;
    def.gravity = {0, 0};
    BodyDef a = body(*box_shape(side, side), {-1.0, 0});
    BodyDef b = body(*box_shape(side, side), {1.0, 0});
    a.velocity = {v, 0};
    b.velocity = {-v, 0};
    def.bodies = {a, b};
    World world(def);
    const int steps = 20;
    for (int k = 0; k < steps; ++k) {
        world.step();
        ASSERT_LT(square_overlap(world.bodies()[0], world.bodies()[1], side), 1e-9) << "step " << k;
    }
    EXPECT_NEAR(world.bodies()[0].velocity.x, -v, 1e-9 * v);
    EXPECT_NEAR(world.bodies()[1].velocity.x, v, 1e-9 * v);
    EXPECT_NEAR(world.bodies()[0].angular_velocity, 0.0, 1e-9);
    const double t_star = 1.9 / (2 * v), flown = 2 * v * (steps / double(def.rate) - t_star);
    EXPECT_NEAR(world.bodies()[1].position.x - world.bodies()[0].position.x, side + flown, 3e-4);
}

INSTANTIATE_TEST_SUITE_P(Speeds, BoxesHeadOn, ::testing::Values(30.0, 300.0, 500.0, 1000.0));

// A box at 300 m/s crossing the path of another at 300 m/s at right angles, offset so that
// their corners meet (a speculative contact made where the step starts sees faces 1.9 m apart
// along the wrong axis). They never overlap, and momentum is kept.
TEST(FastBodies, CrossingBoxesMeetCornerToCorner) {
    const double side = 0.1;
    for (const double offset : {0.0, 0.03, 0.07, 0.095}) {
        WorldDef def;
        def.gravity = {0, 0};
        BodyDef a = body(*box_shape(side, side), {-1.0, 0});
        BodyDef b = body(*box_shape(side, side), {offset, 1.0});
        a.velocity = {300, 0};
        b.velocity = {0, -300};
        def.bodies = {a, b};
        World world(def);
        for (int k = 0; k < 10; ++k) {
            world.step();
            ASSERT_LT(square_overlap(world.bodies()[0], world.bodies()[1], side), 1e-9)
                << "offset " << offset << ", step " << k;
        }
        const BodyState &sa = world.bodies()[0], &sb = world.bodies()[1];
        EXPECT_NEAR(sa.velocity.x + sb.velocity.x, 300.0, 1e-9) << offset;
        EXPECT_NEAR(sa.velocity.y + sb.velocity.y, -300.0, 1e-9) << offset;
        // They met: neither flies on as it came.
        EXPECT_LT(sa.velocity.x, 299.0) << offset;
    }
}

// 64 elastic, frictionless 10 cm boxes at 30 m/s in random directions in a closed 3 m box, no
// gravity, for half a second: each crosses 1.25 of its half-widths per step and meets the
// others and the walls hundreds of times. A gas of boxes is chaotic, so one seed of its throws
// says little: over 12 seeds the median of each run's deepest overlap (after any step) stays
// under 15 % of a half-width, every run's energy within 7 % of its start, and every box inside.
// Measured: median 5.3 %, 0 to 155 % (two boxes meeting corner to corner while a third strikes
// one of them); energy -4.9 % to +4.8 %. (At 10 and 100 m/s: docs/physics.md, "Limits".)
TEST(FastBodies, ABoxGasAt30MetresASecondKeepsApartAndItsEnergy) {
    const double v = 30, side = 0.1;
    std::vector<double> deepest_of_run;
    for (const std::uint64_t seed : {11, 101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111}) {
        WorldDef def;
        def.gravity = {0, 0};
        def.walls.push_back(testing::box({0, 0}, {3, 3}));
        testing::Rng rng(seed);
        for (int k = 0; k < 64; ++k) {
            BodyDef d = body(*box_shape(side, side), {0.3 + 0.34 * (k % 8), 0.3 + 0.34 * (k / 8)});
            const double angle = rng.uniform(0, 2 * M_PI);
            d.velocity = {v * std::cos(angle), v * std::sin(angle)};
            d.angle = rng.uniform(0, M_PI);
            def.bodies.push_back(d);
        }
        World world(def);
        const double start = world.energy();
        double deepest = 0;
        for (int k = 0; k < world.rate() / 2; ++k) {
            world.step();
            const auto discs = world.bodies();
            for (std::size_t i = 0; i < discs.size(); ++i) {
                for (std::size_t j = i + 1; j < discs.size(); ++j) {
                    deepest = std::max(deepest, square_overlap(discs[i], discs[j], side));
                }
            }
        }
        deepest_of_run.push_back(deepest);
        EXPECT_NEAR(world.energy(), start, 0.07 * start) << "seed " << seed;
        for (const BodyState& s : world.bodies()) {
            EXPECT_GT(std::min(s.position.x, s.position.y), 0.0) << "seed " << seed;
            EXPECT_LT(std::max(s.position.x, s.position.y), 3.0) << "seed " << seed;
        }
    }
    std::sort(deepest_of_run.begin(), deepest_of_run.end());
    const double median = 0.5 * (deepest_of_run[5] + deepest_of_run[6]);
    EXPECT_LT(median, 0.15 * side / 2);
}

}  // namespace
}  // namespace discreel::physics

namespace discreel::physics {
namespace {

// A box at 10 km/s into 200 pentagons and boxes at rest: its path crosses all of them in a
// step, and each impact would sweep it against all of them again. The sweeps a step may take
// are bounded (512 per body, plus 1 024); past them a body stays where its last impact left it.
// Before the bound, one 1/60 s frame of such a scene took over 30 s.
TEST(FastBodies, AFastBodyIntoACrowdOfShapesCostsBoundedWork) {
    WorldDef def;
    def.walls = {testing::box({0, 0}, {12, 12})};
    const std::array<Vec2, 5> pentagon{{{0.12, 0}, {0.04, 0.11}, {-0.1, 0.07}, {-0.1, -0.07},
                                        {0.04, -0.11}}};
    const Shape five = polygon_shape(pentagon)->shape;
    const Shape square = *box_shape(0.2, 0.2);
    for (int k = 0; k < 200; ++k) {
        const Vec2 at{2.0 + 0.45 * (k % 20), 0.3 + 0.45 * (k / 20)};
        def.bodies.push_back(body(k % 2 == 0 ? five : square, at));
    }
    BodyDef bullet = body(*box_shape(0.3, 0.3), {0.5, 2.0});
    bullet.velocity = {10000, 300};
    def.bodies.push_back(bullet);
    World world(def);
    // The box of walls is four bodies of the solver's too.
    const std::size_t budget = 512 * (def.bodies.size() + 4) + 1024;
    const auto started = std::chrono::steady_clock::now();
    for (int step = 0; step < 8; ++step) {
        world.step();
        ASSERT_FALSE(world.failure()) << "step " << step;
        EXPECT_LE(world.stats().sweeps, budget) << "step " << step;
    }
    // A frame at 60 fps: under a second in Release; the bound leaves room for sanitizers.
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(30));
    for (const BodyState& s : world.bodies()) {
        EXPECT_GT(s.position.x, 0.0);
        EXPECT_LT(s.position.x, 12.0);
        EXPECT_GT(s.position.y, 0.0);
        EXPECT_LT(s.position.y, 12.0);
    }
}

}  // namespace
}  // namespace discreel::physics

// Heavy against light, to a mass ratio of 1e6: small islands of contacts are solved directly
// (src/physics/island.hpp; for plain discs src/physics/disc_islands.cpp), so a light body
// carries any weight and is never squeezed through. The disc tests run twice: with plain discs
// (the disc solver) and with circle shapes (the manifold solver). Tolerances are the issue's:
// overlap under 0.1 % of the light body's radius at rest, under 1 % in a squeeze; the
// squeeze's end velocities to 1e-6 of the closing speed.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::body;
using testing::Material;

// A circle body: a disc that the manifold solver steps.
BodyDef circle(Vec2 position, Vec2 velocity, double radius, double mass, Material material) {
    BodyDef d = testing::disc(position, velocity, radius, mass, material);
    d.shape = circle_shape(radius);
    return d;
}

enum class Solver { disc, manifold };

// A plain disc (the disc solver's) or a circle body (the manifold solver's).
BodyDef disc_for(Solver solver, Vec2 position, Vec2 velocity, double radius, double mass,
                 Material material) {
    return solver == Solver::manifold ? circle(position, velocity, radius, mass, material)
                                      : testing::disc(position, velocity, radius, mass, material);
}

std::string solver_name(Solver solver) {
    return solver == Solver::manifold ? "Manifold" : "Disc";
}

constexpr Material sticky{.restitution = 0.0, .friction = 0.5};

WorldDef on_floor() {
    WorldDef def;
    def.walls.push_back(testing::box({-5, 0}, {5, 10}, sticky));
    return def;
}

// The deepest overlap between bodies over `seconds`, after the first `settle` steps (m).
double deepest_overlap(World& world, double seconds) {
    double deepest = 0;
    for (int k = 0; k < static_cast<int>(seconds * world.rate()); ++k) {
        world.step();
        deepest = std::max(deepest, world.stats().max_overlap);
    }
    return deepest;
}

// Test names: "Ratio1e4" for 1e4.
std::string ratio_name(const ::testing::TestParamInfo<double>& info) {
    const long exponent = std::lround(std::log10(info.param));
    std::string name = "Ratio1e";
    name.push_back(static_cast<char>('0' + exponent));
    return name;
}

class HeavyOnLight : public ::testing::TestWithParam<double> {};
class DiscOnLight : public ::testing::TestWithParam<std::tuple<Solver, double>> {};

TEST_P(DiscOnLight, RestsOnALightDiscWithinATenthOfAPercentOfItsRadius) {
    const auto [solver, ratio] = GetParam();
    const double r = 0.1;
    WorldDef def = on_floor();
    def.bodies.push_back(disc_for(solver, {0, r}, {0, 0}, r, 1.0, sticky));
    def.bodies.push_back(disc_for(solver, {0, 2 * r + 0.5}, {0, 0}, 0.5, ratio, sticky));
    World world(def);
    EXPECT_EQ(world.manifold_solver(), solver == Solver::manifold);
    EXPECT_LT(deepest_overlap(world, 3.0), 1e-3 * r);
    EXPECT_NEAR(world.bodies()[1].position.y, 2 * r + 0.5, 1e-3 * r);
}

INSTANTIATE_TEST_SUITE_P(Ratios, DiscOnLight,
                         ::testing::Combine(::testing::Values(Solver::disc, Solver::manifold),
                                            ::testing::Values(1e1, 1e2, 1e3, 1e4, 1e6)),
                         [](const auto& info) {
                             const long exponent = std::lround(std::log10(std::get<1>(info.param)));
                             return solver_name(std::get<0>(info.param)) + "Ratio1e" +
                                    std::to_string(exponent);
                         });

TEST_P(HeavyOnLight, BoxRestsOnALightBoxWithinATenthOfAPercentOfItsSize) {
    const double ratio = GetParam(), side = 0.2;
    WorldDef def = on_floor();
    def.bodies.push_back(body(*box_shape(side, side), {0, side / 2}, 1 / (side * side), sticky));
    // A 1 x 0.5 m box of `ratio` kg.
    def.bodies.push_back(body(*box_shape(1, 0.5), {0.03, side + 0.25}, 2 * ratio, sticky));
    World world(def);
    EXPECT_LT(deepest_overlap(world, 3.0), 1e-3 * side / 2);
    EXPECT_NEAR(world.bodies()[1].position.y, side + 0.25, 1e-3 * side / 2);
    EXPECT_NEAR(world.bodies()[1].angle, 0, 1e-4);   // 0.5 mm slop over 0.2 m: 2.5e-3
}

INSTANTIATE_TEST_SUITE_P(Ratios, HeavyOnLight, ::testing::Values(1e2, 1e3, 1e4, 1e6),
                         ratio_name);

// A light disc between two discs 1e6 times heavier that close at 12 m/s: never squeezed
// through, and the heavies leave as one elastic-or-not collision of the two would make them
// (the light one carries the force): -+ e 6 m/s, the same step, reported as one event each.
class Squeeze : public ::testing::TestWithParam<std::tuple<Solver, double>> {};

TEST_P(Squeeze, ALightDiscBetweenTwoMillionTimesHeavierOnesIsNotSqueezedThrough) {
    const auto [solver, e] = GetParam();
    const double r = 0.1, heavy = 1e6;
    WorldDef def;
    def.gravity = {0, 0};
    const Material material{.restitution = e, .friction = 0.0};
    def.bodies.push_back(disc_for(solver, {-1, 0}, {6, 0}, 0.5, heavy, material));
    def.bodies.push_back(disc_for(solver, {0, 0}, {0, 0}, r, 1.0, material));
    def.bodies.push_back(disc_for(solver, {1, 0}, {-6, 0}, 0.5, heavy, material));
    World world(def);
    EXPECT_EQ(world.manifold_solver(), solver == Solver::manifold);
    EXPECT_LT(deepest_overlap(world, 1.0), 1e-2 * r);
    // Each heavy disc's collision is one contact event carrying its change of momentum,
    // (1 + e) 6e6 N s (1e-9 of it: the light disc's share and rounding).
    const std::vector<ContactEvent> events = world.take_events();
    ASSERT_EQ(events.size(), 2U);
    for (const ContactEvent& event : events) {
        EXPECT_EQ(event.other_kind, ContactEvent::Other::body);
        EXPECT_NEAR(event.impulse, (1 + e) * 6 * heavy, 1e-9 * (1 + e) * 6 * heavy);
    }
    EXPECT_NEAR(world.bodies()[0].velocity.x, -e * 6, 6e-6);
    EXPECT_NEAR(world.bodies()[2].velocity.x, e * 6, 6e-6);
    EXPECT_NEAR(world.bodies()[1].position.x, 0, 1e-3 * r);
}

INSTANTIATE_TEST_SUITE_P(Restitutions, Squeeze,
                         ::testing::Combine(::testing::Values(Solver::disc, Solver::manifold),
                                            ::testing::Values(0.0, 0.5, 1.0)),
                         [](const auto& info) {
                             const double e = std::get<1>(info.param);
                             return solver_name(std::get<0>(info.param)) +
                                    (e == 0 ? "Plastic" : e == 1 ? "Elastic" : "Half");
                         });

// A slab 1e5 times heavier than each of the two discs it lies on does not sink into them.
TEST(HeavyLight, ASlabOnTwoLightDiscsDoesNotSinkIntoThem) {
    const double r = 0.1;
    WorldDef def = on_floor();
    def.bodies.push_back(circle({-0.6, r}, {0, 0}, r, 1.0, sticky));
    def.bodies.push_back(circle({0.6, r}, {0, 0}, r, 1.0, sticky));
    def.bodies.push_back(body(*box_shape(2, 0.2), {0, 2 * r + 0.1}, 1e5 / 0.4, sticky));
    World world(def);
    EXPECT_LT(deepest_overlap(world, 3.0), 1e-3 * r);
    EXPECT_NEAR(world.bodies()[2].position.y, 2 * r + 0.1, 1e-3 * r);
    EXPECT_NEAR(world.bodies()[2].angle, 0, 1e-6);
}

// Light and heavy boxes alternating up a column, each heavy one `ratio` times its light one:
// after 3 s every box is still within a millimetre of where it started.
class LightUnderHeavy : public ::testing::TestWithParam<double> {};

TEST_P(LightUnderHeavy, AStackHolds) {
    const double ratio = GetParam(), side = 0.2;
    WorldDef def = on_floor();
    for (int k = 0; k < 4; ++k) {
        const double density = (k % 2 ? ratio : 1.0) / (side * side);
        def.bodies.push_back(body(*box_shape(side, side), {0, side * (k + 0.5)}, density, sticky));
    }
    World world(def);
    const double deepest = deepest_overlap(world, 3.0);
    EXPECT_LT(deepest, 1e-3 * side / 2);
    for (int k = 0; k < 4; ++k) {
        const BodyState& s = world.bodies()[static_cast<std::size_t>(k)];
        EXPECT_LT(std::hypot(s.position.x, s.position.y - side * (k + 0.5)), 1e-3) << "box " << k;
    }
}

INSTANTIATE_TEST_SUITE_P(Ratios, LightUnderHeavy, ::testing::Values(1e2, 1e3, 1e4),
                         ratio_name);

// A box 1e6 times heavier than the one beside it (one island through their contact) lands flat
// from 1 m with e = 0.5 and rebounds to e^2 h, as a box alone does (Bodies.*: 2 %).
TEST(HeavyLight, ABoxBesideOneAMillionTimesLighterLandsAndReboundsToESquaredH) {
    const double e = 0.5, h = 1.0;
    WorldDef def;
    def.walls.push_back(testing::box({-5, 0}, {5, 10}, {.restitution = e, .friction = 0.5}));
    const Material material{.restitution = e, .friction = 0.5};
    def.bodies.push_back(body(*box_shape(1, 0.5), {-0.5, 0.25 + h}, 1e6, material));
    def.bodies.push_back(body(*box_shape(1, 0.5), {0.5, 0.25 + h}, 1, material));
    World world(def);
    const std::optional<double> top = testing::rebound_height(world, 0, 0.25);
    ASSERT_TRUE(top);
    EXPECT_NEAR(*top, e * e * h, 0.02 * e * e * h);
}

// A box 1e6 times heavier lands from 0.5 m on a light box resting on the floor, e = 0.5: it
// rebounds to e^2 h as off the floor itself (2 %, as Bodies.*), the light box stays where it
// was (1 mm) and the energy never rises (1e-6 of the start, rounding). The bounce pushes the
// light box into the floor, which must push back in the same step: bounced alone it left
// through the floor at e times the heavy one's momentum.
TEST(HeavyLight, AHeavyBoxLandingOnALightOneReboundsAndLeavesItInPlace) {
    const double e = 0.5, h = 0.5, side = 0.2;
    WorldDef def;
    const Material material{.restitution = e, .friction = 0.5};
    def.walls.push_back(testing::box({-5, 0}, {5, 10}, material));
    def.bodies.push_back(body(*box_shape(side, side), {0, side / 2}, 1 / (side * side), material));
    def.bodies.push_back(body(*box_shape(1, 0.5), {0, side + 0.25 + h}, 1e6 / 0.5, material));
    World world(def);
    const double start = world.energy();
    double highest = start;
    const std::optional<double> top =
        testing::rebound_height(world, 1, side + 0.25, [&](const BodyState&) {
            highest = std::max(highest, world.energy());
        });
    ASSERT_TRUE(top);
    EXPECT_NEAR(*top, e * e * h, 0.02 * e * e * h);
    EXPECT_LT(highest, start + 1e-6 * std::abs(start));
    const BodyState& light = world.bodies()[0];
    EXPECT_LT(std::hypot(light.position.x, light.position.y - side / 2), 1e-3);
}

// A light disc rests against a heavy one at `angle` (degrees, from the light one) and another
// heavy one strikes it at 3 m/s along x, e = 0.5, no gravity: the light disc is squeezed out
// sideways. The energy never rises (1e-9 of the start, rounding): bounced by Poisson's rule at
// the point that was struck alone, the light disc had left at e times the impulse that held the
// heavy ones apart (at 1e6: 2e5 m/s, 4 500 times the energy).
class WedgeSqueeze : public ::testing::TestWithParam<std::tuple<Solver, double, double>> {};

TEST_P(WedgeSqueeze, ALightDiscSqueezedOutAddsNoEnergy) {
    const auto [solver, ratio, degrees] = GetParam();
    const double r = 0.4, angle = degrees * 3.141592653589793 / 180;
    const Material material{.restitution = 0.5, .friction = 0.5};
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies.push_back(disc_for(solver, {2 * r * std::cos(angle), 2 * r * std::sin(angle)},
                                  {0, 0}, r, ratio, material));
    def.bodies.push_back(disc_for(solver, {0, 0}, {0, 0}, r, 1.0, material));
    def.bodies.push_back(disc_for(solver, {2 * r + 0.01, 0}, {-3, 0}, r, ratio, material));
    World world(def);
    const double start = world.energy();
    double highest = start;
    for (int k = 0; k < world.rate(); ++k) {
        world.step();
        highest = std::max(highest, world.energy());
    }
    EXPECT_LE(highest, start * (1 + 1e-9));
}

INSTANTIATE_TEST_SUITE_P(
    RatiosAndAngles, WedgeSqueeze,
    ::testing::Combine(::testing::Values(Solver::disc, Solver::manifold),
                       ::testing::Values(1e2, 1e4, 1e6), ::testing::Values(150.0, 165.0, 170.0)),
    [](const auto& info) {
        const long exponent = std::lround(std::log10(std::get<1>(info.param)));
        return solver_name(std::get<0>(info.param)) + "Ratio1e" + std::to_string(exponent) +
               "At" + std::to_string(std::lround(std::get<2>(info.param)));
    });

// 64 circles in a 10 m box, every other one 1 000 times heavier, thrown at 2 m/s, e = 0.5
// (extremes_test.cpp's scene): one island too large to solve whole, iterated by blocks. It
// stays bounded: no body faster than a fall across the box gives (14 m/s), overlap under half a
// radius (measured: 8.1 m/s, 0.27 r; iterated pair by pair it reached 2e4 m/s).
WorldDef crowd(double ratio, int seed, bool boxes) {
    WorldDef def;
    const Material material{.restitution = 0.5, .friction = 0.5};
    def.walls.push_back(testing::box({0, 0}, {10, 10}, material));
    testing::Rng rng(static_cast<std::uint64_t>(seed));
    for (int k = 0; k < 64; ++k) {
        const double angle = rng.uniform(0, 2 * 3.141592653589793);
        const int column = k % 8, row = k / 8;
        const Vec2 at{(1 + column) * 1.1, (1 + row) * 1.1};
        const Vec2 velocity{2 * std::cos(angle), 2 * std::sin(angle)};
        const double mass = k % 2 ? ratio : 1.0;
        BodyDef d = circle(at, velocity, 0.4, mass, material);
        if (boxes) d.shape = *box_shape(0.8, 0.8);
        def.bodies.push_back(d);
    }
    return def;
}

TEST(HeavyLight, ALargeIslandOfMassesAThousandApartStaysBounded) {
    World world(crowd(1000, 7, false));
    double overlap = 0;
    for (int k = 0; k < 2 * world.rate(); ++k) {
        world.step();
        overlap = std::max(overlap, world.stats().max_overlap_ratio);
    }
    double fastest = 0;
    for (const BodyState& s : world.bodies()) {
        fastest = std::max(fastest, std::hypot(s.velocity.x, s.velocity.y));
    }
    EXPECT_LT(fastest, 14.0);
    EXPECT_LT(overlap, 0.5);
}

// The crowd above at other ratios and seeds, circles and 0.8 m boxes, for as long as it took
// to go wrong: its energy never rises by 1 % of the start between two 60 fps frames. The warm
// start's impulses, which iterations between masses far apart take back slowly, rose it by
// 11 % (circles, 1e2, at 0.83 s) and 2.9 times (boxes, 1e6, at 0.55 s); bounced by Poisson's
// rule, a light body wedged between heavy ones by 3.2 times (circles, 1e4, at 0.55 s).
class Crowd : public ::testing::TestWithParam<std::tuple<double, int, bool, double>> {};

TEST_P(Crowd, OfMassesFarApartGainsNoEnergyBetweenFrames) {
    const auto [ratio, seed, boxes, seconds] = GetParam();
    World world(crowd(ratio, seed, boxes));
    const double start = world.energy();
    double frame = start, rise = 0;
    for (int k = 1; k <= static_cast<int>(seconds * world.rate()); ++k) {
        world.step();
        if (k % (world.rate() / 60) != 0) continue;
        rise = std::max(rise, world.energy() - frame);
        frame = world.energy();
    }
    EXPECT_LT(rise, 0.01 * start);
}

INSTANTIATE_TEST_SUITE_P(Seeds, Crowd,
                         ::testing::Values(std::tuple{1e2, 3, false, 0.9},
                                           std::tuple{1e4, 2, false, 0.6},
                                           std::tuple{1e6, 6, true, 0.6}),
                         [](const auto& info) {
                             const double ratio = std::get<0>(info.param);
                             return std::string(std::get<2>(info.param) ? "Boxes" : "Circles") +
                                    "Ratio1e" + std::to_string(std::lround(std::log10(ratio))) +
                                    "Seed" + std::to_string(std::get<1>(info.param));
                         });

// limits_bench's crowd: 64 boxes of side 0.8 m in a 10 m box, every other one `ratio` times
// heavier, thrown in the directions of generator 7 at `radii_per_step` times 0.4 m a step.
constexpr double crowd_side = 10;
WorldDef thrown_boxes(double ratio, double radii_per_step) {
    constexpr double r = 0.4;
    WorldDef def;
    const Material material{.restitution = 0.5, .friction = 0.5};
    def.walls.push_back(testing::box({0, 0}, {crowd_side, crowd_side}, material));
    testing::Rng rng(7);
    const double speed = radii_per_step * r * def.rate;
    for (int k = 0; k < 64; ++k) {
        const double angle = rng.uniform(0, 2 * 3.141592653589793);
        BodyDef d = circle({(1 + k % 8) * 1.1, (1 + k / 8) * 1.1},
                           {speed * std::cos(angle), speed * std::sin(angle)}, r,
                           k % 2 ? ratio : 1.0, material);
        d.shape = *box_shape(2 * r, 2 * r);
        def.bodies.push_back(d);
    }
    return def;
}

void expect_inside(const World& world) {
    for (const BodyState& s : world.bodies()) {
        EXPECT_GT(std::min(s.position.x, s.position.y), 0.0);
        EXPECT_LT(std::max(s.position.x, s.position.y), crowd_side);
    }
}

// limits_bench's crowd of boxes, every other one 1e3 or 1e4 times heavier, thrown at a hundredth
// of a half-width per step (1.9 m/s, within the envelope's speed for such ratios). An island or
// block of masses far apart is pushed out as if none of its bodies were over 10 times heavier
// than its lightest, so a heavy box driving a light one into a third is pushed back too: with
// true masses only the light box moved, from one neighbour into the next, and a heavy box sank
// through a light one at 3 m/s (79 and 112 % of the half-width within the second). The bounds:
// deepest overlap under 35 % of the half-width (7.8 and 12 % measured), and the energy rising
// by under 1 % of the start between 60 fps frames (under 0.001 % measured).
class BoxCrowd : public ::testing::TestWithParam<double> {};

TEST_P(BoxCrowd, HoldsApartWithoutGainingEnergy) {
    constexpr double half_width = 0.4;
    World world(thrown_boxes(GetParam(), 0.01));
    const double start = world.energy();
    double frame = start, rise = 0, deepest = 0;
    for (int k = 1; k <= world.rate(); ++k) {
        world.step();
        deepest = std::max(deepest, world.stats().max_overlap);
        if (k % 8 != 0) continue;
        rise = std::max(rise, world.energy() - frame);
        frame = world.energy();
    }
    EXPECT_LT(deepest, 0.35 * half_width);
    EXPECT_LT(rise, 0.01 * start);
    expect_inside(world);
}

INSTANTIATE_TEST_SUITE_P(Ratios, BoxCrowd, ::testing::Values(1e3, 1e4), ratio_name);

// limits_bench's crowd of boxes 100 times apart thrown at 10 radii per step (1 920 m/s): its
// first steps push out block islands (larger islands of masses 100 apart) before the sweeps
// over the other contacts, which once wrote past the push-out's per-body records (a crash in
// Release, an error under ASan). It stays finite, and every box inside its walls.
TEST(HeavyLight, BoxesFarApartInMassThrownFastStayFiniteAndInside) {
    World world(thrown_boxes(100, 10));
    for (int k = 0; k < world.rate() / 4; ++k) world.step();
    ASSERT_FALSE(world.failure().has_value());
    expect_inside(world);
}

// limits_bench's crowd of boxes 1e6 times apart thrown at 1 radius per step: at 1.38 s a light
// box is crushed between the left wall and a heavy box whose face leans by under a degree, and
// the only way out is along the slant. Its block island's push-out (one LCP for the block)
// slid it 11 m at once, out of its container, and the next step launched it at 4e4 m/s: the
// crowd's energy rose 17 times between two frames. An island's push-out now moves a body at
// most its inner radius a sweep (held to 2 cm, the box was pushed through the wall instead);
// the energy rises by at most 0.001 % of the start, and every box stays inside.
TEST(HeavyLight, ACrushedLightBoxIsPushedOutInSmallSteps) {
    World world(thrown_boxes(1e6, 1));
    const double start = world.energy();
    double frame = start, rise = 0;
    for (int k = 1; k <= 700; ++k) {
        world.step();
        if (k % 8 != 0) continue;
        rise = std::max(rise, world.energy() - frame);
        frame = world.energy();
    }
    EXPECT_LT(rise, 0.01 * start);
    expect_inside(world);
}

}  // namespace
}  // namespace discreel::physics

// The far ends of what a scene may ask for: masses from 1e-6 to 1e6 kg in one pile, speeds
// of 1e4 m/s, discs from micrometres to kilometres. Every scene stays finite and inside its
// box. Inside the envelope the scene loader accepts (mass ratio between dynamic discs up to
// 1e3, speed per step up to 10 / mass ratio^(2/3) radii; docs/physics.md has the table) discs
// also barely overlap and energy never rises; beyond it, discs pass through each other and
// a heavy pile can be lifted a little by position correction, which is why it is rejected.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

using testing::disc;

struct Extreme {
    std::string name;
    double scale = 1.0;        // every length (and speed) multiplied by this
    double light = 1.0;        // kg, every other disc
    double heavy = 1.0;        // kg
    double speed = 2.0;        // m/s before scaling, random directions
    double gravity = 9.81;     // m/s^2 before scaling
    bool in_envelope = true;   // what the scene loader accepts
};

std::string name_of(const ::testing::TestParamInfo<Extreme>& info) { return info.param.name; }

// 64 discs on a loose grid in a closed box, half of them `light` and half `heavy`, thrown in
// random directions; 2 simulated seconds.
WorldDef extreme_world(const Extreme& e) {
    WorldDef def;
    def.gravity = {0, -e.gravity * e.scale};
    const testing::Material material{.restitution = 0.5, .friction = 0.5};
    def.walls.push_back(testing::box({0, 0}, {10 * e.scale, 10 * e.scale}, material));
    testing::Rng rng(7);
    for (int k = 0; k < 64; ++k) {
        const double angle = rng.uniform(0, 2 * 3.141592653589793);
        const Vec2 position{(1 + k % 8) * 1.1 * e.scale, (1 + k / 8) * 1.1 * e.scale};
        const Vec2 velocity{e.speed * e.scale * std::cos(angle), e.speed * e.scale * std::sin(angle)};
        def.bodies.push_back(
            disc(position, velocity, 0.4 * e.scale, k % 2 ? e.heavy : e.light, material));
    }
    return def;
}

class ExtremeTest : public ::testing::TestWithParam<Extreme> {};

TEST_P(ExtremeTest, StaysFiniteAndInsideItsBox) {
    const Extreme& e = GetParam();
    const WorldDef def = extreme_world(e);
    World world(def);
    const double start = world.energy();
    const double radius = 0.4 * e.scale, side = 10 * e.scale;
    double deepest = 0;        // into a wall, as a fraction of the radius
    double overlap = 0;        // between discs, as a fraction of the smaller radius
    double rise = 0;           // of energy between 60 fps frames, relative to the start
    double frame_energy = start;
    for (int k = 0; k < 2 * def.rate; ++k) {
        world.step();
        ASSERT_FALSE(world.failure()) << "step " << k;
        for (std::size_t i = 0; i < world.bodies().size(); ++i) {
            const BodyState& s = world.bodies()[i];
            ASSERT_TRUE(std::isfinite(s.position.x) && std::isfinite(s.position.y) &&
                        std::isfinite(s.velocity.x) && std::isfinite(s.velocity.y) &&
                        std::isfinite(s.angle) && std::isfinite(s.angular_velocity))
                << "disc " << i << " at step " << k;
            const double clearance = std::min({s.position.x, s.position.y, side - s.position.x,
                                               side - s.position.y});
            deepest = std::max(deepest, 1 - clearance / radius);
        }
        overlap = std::max(overlap, world.stats().max_overlap_ratio);
        if (k % (def.rate / 60) == def.rate / 60 - 1) {
            const double energy = world.energy();
            rise = std::max(rise, (energy - frame_energy) / std::abs(start));
            frame_energy = energy;
        }
    }
    // Walls win over every other contact, and a disc sent farther than it could have gone is
    // stopped at the first wall on its path, so no disc ends a step deeper in a wall than the
    // thousandth of its radius left untested (docs/physics.md), at any mass or speed.
    EXPECT_LT(deepest, 1.5e-3);
    if (!e.in_envelope) return;
    // Inside the envelope the overlap stays near a tenth of the radius (docs/physics.md,
    // "Limits"); 0.3 leaves room for other seeds, not for discs passing through each other.
    EXPECT_LT(overlap, 0.3);
    // Restitution 0.5 and friction only ever take energy out; the energy tests allow a rise of
    // 0.1 % between frames for rounding, and the envelope stays well within that.
    EXPECT_LT(rise, 1e-3);
    EXPECT_LE(world.energy(), start + 1e-3 * std::abs(start));
}

INSTANTIATE_TEST_SUITE_P(
    Physics, ExtremeTest,
    ::testing::Values(
        // Inside the envelope.
        Extreme{.name = "Reference"},
        Extreme{.name = "AllLight", .light = 1e-6, .heavy = 1e-6},
        Extreme{.name = "AllHeavy", .light = 1e6, .heavy = 1e6},
        Extreme{.name = "Micrometres", .scale = 1e-6},
        Extreme{.name = "Megametres", .scale = 1e6},
        Extreme{.name = "MassRatio1e3", .light = 1, .heavy = 1e3},
        Extreme{.name = "MassRatio1e3At10", .light = 1, .heavy = 1e3, .speed = 10},
        Extreme{.name = "MassRatio1e2At35", .light = 1, .heavy = 1e2, .speed = 35},
        Extreme{.name = "MassRatio10At100", .light = 1, .heavy = 10, .speed = 1e2},
        Extreme{.name = "Speed3e2", .speed = 3e2},
        // At its edges: r = 0.4 m at 480 Hz is 192 m/s per radius per step.
        Extreme{.name = "Speed1900", .speed = 1900},
        Extreme{.name = "MassRatio10At400", .light = 1, .heavy = 10, .speed = 400},
        Extreme{.name = "MassRatio1e2At88", .light = 1, .heavy = 1e2, .speed = 88},
        Extreme{.name = "MassRatio1e3At19", .light = 1, .heavy = 1e3, .speed = 19},
        // Beyond it: finite and inside the box only.
        Extreme{.name = "MassRatio1e12", .light = 1e-6, .heavy = 1e6, .in_envelope = false},
        Extreme{.name = "Speed1e4", .speed = 1e4, .in_envelope = false},
        Extreme{.name = "Speed1e4MassRatio1e12", .light = 1e-6, .heavy = 1e6, .speed = 1e4,
                .in_envelope = false},
        Extreme{.name = "Speed5e2MassRatio1e3", .light = 1, .heavy = 1e3, .speed = 5e2,
                .in_envelope = false},
        Extreme{.name = "Speed5e2MassRatio1e2", .light = 1, .heavy = 1e2, .speed = 5e2,
                .in_envelope = false},
        Extreme{.name = "Speed9e1MassRatio1e2", .light = 1, .heavy = 1e2, .speed = 90,
                .in_envelope = false}),
    name_of);

// The same boxes as circle shapes (the manifold solver), where walls win too: no circle ends a
// step deeper in a wall than the thousandth of its radius. A light circle under a heavy one
// was left 0.4 % of its radius in the floor (the push-out shares each push between the two),
// and a circle spinning as it met a wall at 300 m/s 5 % (its anchor turned off the contact).
class ExtremeCircles : public ::testing::TestWithParam<Extreme> {};

TEST_P(ExtremeCircles, StayOutOfTheWalls) {
    const Extreme& e = GetParam();
    WorldDef def = extreme_world(e);
    for (BodyDef& d : def.bodies) d.shape = circle_shape(d.radius);
    World world(def);
    ASSERT_TRUE(world.manifold_solver());
    const double radius = 0.4 * e.scale, side = 10 * e.scale;
    double deepest = 0;   // into a wall, as a fraction of the radius
    for (int k = 0; k < 2 * def.rate; ++k) {
        world.step();
        ASSERT_FALSE(world.failure()) << "step " << k;
        for (const BodyState& s : world.bodies()) {
            const double clearance = std::min({s.position.x, s.position.y, side - s.position.x,
                                               side - s.position.y});
            deepest = std::max(deepest, 1 - clearance / radius);
        }
    }
    EXPECT_LT(deepest, 1.5e-3);
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, ExtremeCircles,
    ::testing::Values(Extreme{.name = "Reference"},
                      Extreme{.name = "MassRatio1e3", .light = 1, .heavy = 1e3},
                      Extreme{.name = "MassRatio1e3At10", .light = 1, .heavy = 1e3, .speed = 10},
                      Extreme{.name = "Speed1e2", .speed = 1e2},
                      Extreme{.name = "Speed3e2", .speed = 3e2}),
    name_of);

}  // namespace
}  // namespace discreel::physics

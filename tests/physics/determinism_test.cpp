// Same scene, same bits: a busy scene hashed after two seconds, compared across runs and with a
// pinned value (which changes only when the solver does; update it deliberately then).
#include <cstdint>
#include <cstring>

#include <gtest/gtest.h>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics {
namespace {

WorldDef busy_scene() {
    WorldDef def = testing::pile({.count = 500, .seed = 42});
    def.walls.push_back(testing::segment({1, 5}, {8, 3}, 0.05, {.restitution = 0.6, .friction = 0.4}));
    DiscDef peg = testing::disc({6, 6}, {0, 0}, 0.3, 1.0, {.restitution = 0.6, .friction = 0.4});
    peg.is_static = true;
    def.discs.push_back(peg);
    ThrowDef flick;
    flick.disc = 3;
    flick.at = 0.5;
    flick.velocity = Vec2{40, 25};
    def.throws.push_back(flick);
    ThrowDef grab;
    grab.disc = 100;
    grab.path = {{0.2, {3, 9}}, {0.8, {9, 9}}, {1.0, {5, 2}}};
    def.throws.push_back(grab);
    return def;
}

std::uint64_t state_hash(const World& world) {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a
    auto mix = [&h](double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int k = 0; k < 8; ++k) {
            h ^= (bits >> (8 * k)) & 0xff;
            h *= 1099511628211ull;
        }
    };
    for (const DiscState& s : world.discs()) {
        mix(s.position.x);
        mix(s.position.y);
        mix(s.velocity.x);
        mix(s.velocity.y);
        mix(s.angle);
        mix(s.angular_velocity);
    }
    return h;
}

std::uint64_t run_busy_scene() {
    World world(busy_scene());
    testing::run_for(world, 2.0);
    return state_hash(world);
}

TEST(Determinism, BusySceneGivesTheSameBitsEveryRun) {
    const std::uint64_t first = run_busy_scene();
    EXPECT_EQ(run_busy_scene(), first);
    EXPECT_EQ(first, 14852217680573341731ull) << first;
}

}  // namespace
}  // namespace discreel::physics

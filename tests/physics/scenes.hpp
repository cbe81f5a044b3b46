#pragma once
// Scene builders shared by the physics tests.
#include <cmath>
#include <cstdint>
#include <vector>

#include "discreel/physics.hpp"

namespace discreel::physics::testing {

inline DiscDef disc(Vec2 position, Vec2 velocity, double radius, double mass,
                    double restitution = 1.0, double friction = 0.0) {
    DiscDef d;
    d.position = position;
    d.velocity = velocity;
    d.radius = radius;
    d.mass = mass;
    d.restitution = restitution;
    d.friction = friction;
    return d;
}

inline WallDef box(Vec2 lo, Vec2 hi, double restitution = 1.0, double friction = 0.0) {
    WallDef w;
    w.shape = WallDef::Shape::box;
    w.a = lo;
    w.b = hi;
    w.restitution = restitution;
    w.friction = friction;
    return w;
}

inline WallDef segment(Vec2 a, Vec2 b, double thickness, double restitution = 1.0,
                       double friction = 0.0) {
    WallDef w;
    w.shape = WallDef::Shape::segment;
    w.a = a;
    w.b = b;
    w.thickness = thickness;
    w.restitution = restitution;
    w.friction = friction;
    return w;
}

// A small deterministic generator (splitmix64) so scenes do not depend on <random>'s
// implementation-defined distributions.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    double uniform(double lo, double hi) {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
    }

private:
    std::uint64_t state_;
};

// Discs of radius r on a grid in a box of side spacing * columns, small random velocities.
inline WorldDef pile(int count, double radius, double spacing, double restitution,
                     double friction, Vec2 gravity, double speed, std::uint64_t seed) {
    WorldDef def;
    def.gravity = gravity;
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    const double side = spacing * columns;
    def.walls.push_back(box({0, 0}, {side, side}, restitution, friction));
    Rng rng(seed);
    for (int k = 0; k < count; ++k) {
        const double x = spacing * (0.5 + k % columns);
        const double y = spacing * (0.5 + k / columns);
        const double mass = 3.141592653589793 * radius * radius;
        def.discs.push_back(disc({x, y}, {rng.uniform(-speed, speed), rng.uniform(-speed, speed)},
                                 radius, mass, restitution, friction));
    }
    return def;
}

inline void run_for(World& world, double seconds) {
    const auto steps = static_cast<std::int64_t>(std::llround(seconds * 480));
    for (std::int64_t k = 0; k < steps; ++k) world.step();
}

}  // namespace discreel::physics::testing

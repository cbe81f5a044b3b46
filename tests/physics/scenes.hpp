#pragma once
// Scene builders shared by the physics tests.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "discreel/physics.hpp"

namespace discreel::physics::testing {

// What a disc or wall is made of; by default elastic and frictionless, so that a test states
// the losses it wants: testing::disc(..., {.restitution = 0.5}).
struct Material {
    double restitution = 1.0;      // coefficient of restitution, 0..1
    double friction = 0.0;         // Coulomb coefficient, >= 0
};

// position (m), velocity (m/s), radius (m), mass (kg).
inline BodyDef disc(Vec2 position, Vec2 velocity, double radius, double mass,
                    Material material = {}) {
    BodyDef d;
    d.position = position;
    d.velocity = velocity;
    d.radius = radius;
    d.mass = mass;
    d.restitution = material.restitution;
    d.friction = material.friction;
    return d;
}

// A body of any shape (discreel/shapes.hpp) centred at `position` (m), of `density` (kg/m^2).
inline BodyDef body(const Shape& shape, Vec2 position, double density = 1.0,
                    Material material = {}) {
    BodyDef d;
    d.shape = shape;
    d.position = position;
    d.radius = bounding_radius(shape);
    d.mass = shape_mass(shape, density).mass;
    d.restitution = material.restitution;
    d.friction = material.friction;
    return d;
}

// A closed box with corners lo and hi (m).
inline WallDef box(Vec2 lo, Vec2 hi, Material material = {}) {
    WallDef w;
    w.shape = WallDef::Shape::box;
    w.a = lo;
    w.b = hi;
    w.restitution = material.restitution;
    w.friction = material.friction;
    return w;
}

// A capsule from a to b (m), thickness (m) across.
inline WallDef segment(Vec2 a, Vec2 b, double thickness, Material material = {}) {
    WallDef w;
    w.shape = WallDef::Shape::segment;
    w.a = a;
    w.b = b;
    w.thickness = thickness;
    w.restitution = material.restitution;
    w.friction = material.friction;
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

// A pile: `count` equal discs on a square grid, rows filled from the bottom left, in a box of
// side spacing * columns, with random velocities. testing::pile({.count = 400, .seed = 7}).
struct PileDef {
    int count = 100;
    double radius = 0.2;           // metres
    double spacing = 0.5;          // metres between neighbouring centres of the grid
    Material material = {.restitution = 0.6, .friction = 0.4};  // discs and box
    Vec2 gravity{0.0, -9.81};      // m/s^2
    double speed = 2.0;            // m/s: each velocity component is uniform in +-speed
    std::uint64_t seed = 1;        // of the velocities
};

inline WorldDef pile(const PileDef& p) {
    WorldDef def;
    def.gravity = p.gravity;
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(p.count))));
    const double side = p.spacing * columns;
    def.walls.push_back(box({0, 0}, {side, side}, p.material));
    Rng rng(p.seed);
    for (int k = 0; k < p.count; ++k) {
        const double x = p.spacing * (0.5 + k % columns);
        const double y = p.spacing * (0.5 + k / columns);
        const double mass = 3.141592653589793 * p.radius * p.radius;  // kg: 1 kg/m^2
        const Vec2 velocity{rng.uniform(-p.speed, p.speed), rng.uniform(-p.speed, p.speed)};
        def.bodies.push_back(disc({x, y}, velocity, p.radius, mass, p.material));
    }
    return def;
}

// Steps the world through `seconds` (s), rounded to whole steps at its rate.
inline void run_for(World& world, double seconds) {
    const auto steps = static_cast<std::int64_t>(std::llround(seconds * world.rate()));
    for (std::int64_t k = 0; k < steps; ++k) world.step();
}

// Steps `world` for at most 2 s while body i, dropped flat, lands and comes back down: the
// highest its bottom (centre minus half_height, m) gets once it first moves up, or nothing if it
// never does. `each`, if set, sees the body after every step.
inline std::optional<double> rebound_height(
    World& world, std::size_t i, double half_height,
    const std::function<void(const BodyState&)>& each = {}) {
    bool landed = false;
    double top = 0;
    for (int k = 0; k < 2 * world.rate(); ++k) {
        world.step();
        const BodyState& s = world.bodies()[i];
        const double bottom = s.position.y - half_height;
        if (!landed && s.velocity.y > 0) landed = true;
        if (landed) top = std::max(top, bottom);
        if (landed && s.velocity.y < 0 && bottom < 0.01) break;
        if (each) each(s);
    }
    if (!landed) return std::nullopt;
    return top;
}

}  // namespace discreel::physics::testing

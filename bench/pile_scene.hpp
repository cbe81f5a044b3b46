#pragma once
// The pile scene (docs/physics.md, "Speed"): N discs of radius 0.5 and density 1 on a grid with
// small seeded velocities, in a box of side 1.4 ceil(sqrt N) m, g = -9.8, friction 0.6,
// restitution 0.5. physics_bench times it through the disc solver; body_bench as circle shapes,
// through the manifold solver, which every shape's pipeline must match.
#include <cmath>
#include <cstdint>

#include "discreel/physics.hpp"
#include "splitmix.hpp"

namespace discreel::bench {

struct PileSettings {
    int rate = 480;
    int substeps = 0;         // 0: the world's default
    int iterations = 3;       // the disc solver's own (WorldDef::iterations 0)
    std::uint64_t seed = 12345;
    bool circles = false;     // each disc a circle shape: the manifold solver steps the pile
};

inline physics::WorldDef pile(int n, const PileSettings& settings) {
    const double r = 0.5, spacing = 1.4;
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    physics::WorldDef def;
    def.gravity = {0, -9.8};
    def.rate = settings.rate;
    def.substeps = settings.substeps;
    def.iterations = settings.iterations;
    physics::WallDef box;
    box.shape = physics::WallDef::Shape::box;
    box.a = {0, 0};
    box.b = {spacing * columns, spacing * columns};
    box.restitution = 0.5;
    box.friction = 0.6;
    def.walls.push_back(box);
    std::uint64_t seed = settings.seed;
    for (int k = 0; k < n; ++k) {
        physics::BodyDef d;
        d.position = {spacing * (0.5 + k % columns), spacing * (0.5 + k / columns)};
        d.velocity = {uniform(seed, -0.5, 0.5), uniform(seed, -0.5, 0.5)};
        d.radius = r;
        if (settings.circles) d.shape = physics::circle_shape(r);
        d.mass = 3.141592653589793 * r * r;
        d.restitution = 0.5;
        d.friction = 0.6;
        def.bodies.push_back(d);
    }
    return def;
}

}  // namespace discreel::bench

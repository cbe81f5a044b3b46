// heavy_light_bench: heavy against light, per solver and mass ratio, on the scenes Box2D v3
// is measured on (../shared/FIELD_NOTES.md, "Mass ratios and fast bodies"), all r = 0.5 m,
// 480 Hz:
//   rest     a heavy disc resting on a light one on the floor, 3 s: deepest overlap, % of r;
//   squeeze  a light disc between two heavy ones closing at 6 m/s, e = 0, no gravity, 1 s:
//            deepest overlap, % of r;
//   pile     64 discs (r = 0.4), every other one heavy, thrown at 2 m/s in random directions
//            in a 10 m box (tests/physics/extremes_test.cpp), 2 s, with the throws' generator
//            seeded 1 to 9 (a crowd is chaotic: one seed's deepest overlap says little): the
//            median and the worst of the seeds' deepest overlaps (% of r), the largest rise of
//            the energy between 60 fps frames (% of the start) and the fastest disc at the end
//            (m/s; about 2 when it holds), over all seeds.
// "disc" is the disc solver (plain discs), "manifold" the manifold solver (circle shapes);
// both solve small islands directly. Appends to bench/results/heavy_light_bench.csv.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_results.hpp"
#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace {

using namespace discreel;
using namespace discreel::physics;

BodyDef disc(Vec2 position, Vec2 velocity, double radius, double mass, bool manifold,
             double restitution = 0.0, double friction = 0.5) {
    BodyDef d;
    d.position = position;
    d.velocity = velocity;
    d.radius = radius;
    d.mass = mass;
    d.restitution = restitution;
    d.friction = friction;
    if (manifold) d.shape = circle_shape(radius);
    return d;
}

WallDef box(Vec2 lo, Vec2 hi, double restitution) {
    WallDef w;
    w.shape = WallDef::Shape::box;
    w.a = lo;
    w.b = hi;
    w.restitution = restitution;
    w.friction = 0.5;
    return w;
}

double deepest(World& world, double seconds) {
    double depth = 0;
    for (int k = 0; k < static_cast<int>(seconds * world.rate()); ++k) {
        world.step();
        depth = std::max(depth, world.stats().max_overlap);
    }
    return depth;
}

double rest(double ratio, bool manifold) {
    WorldDef def;
    def.walls.push_back(box({-5, 0}, {5, 10}, 0.0));
    def.bodies.push_back(disc({0, 0.5}, {}, 0.5, 1, manifold));
    def.bodies.push_back(disc({0, 1.5}, {}, 0.5, ratio, manifold));
    World world(def);
    return 100 * deepest(world, 3) / 0.5;
}

double squeeze(double ratio, bool manifold) {
    WorldDef def;
    def.gravity = {0, 0};
    def.bodies.push_back(disc({-1.5, 0}, {3, 0}, 0.5, ratio, manifold, 0, 0));
    def.bodies.push_back(disc({0, 0}, {}, 0.5, 1, manifold, 0, 0));
    def.bodies.push_back(disc({1.5, 0}, {-3, 0}, 0.5, ratio, manifold, 0, 0));
    World world(def);
    return 100 * deepest(world, 1) / 0.5;
}

struct Pile {
    double overlap_pct = 0;
    double energy_rise_pct = 0;
    double fastest = 0;   // m/s
};

Pile pile(double ratio, bool manifold, int seed) {
    WorldDef def;
    def.walls.push_back(box({0, 0}, {10, 10}, 0.5));
    testing::Rng rng(seed);  // the scenes' generator, as in tests/physics/extremes_test.cpp
    for (int k = 0; k < 64; ++k) {
        const double angle = rng.uniform(0, 2 * 3.141592653589793);
        const int column = k % 8, row = k / 8;
        def.bodies.push_back(disc({(1 + column) * 1.1, (1 + row) * 1.1},
                                 {2 * std::cos(angle), 2 * std::sin(angle)}, 0.4,
                                 k % 2 ? ratio : 1.0, manifold, 0.5, 0.5));
    }
    World world(def);
    Pile p;
    const double start = world.energy();
    double frame_energy = start, depth = 0;
    for (int k = 0; k < 2 * world.rate(); ++k) {
        world.step();
        depth = std::max(depth, world.stats().max_overlap);
        if (k % (world.rate() / 60) == world.rate() / 60 - 1) {
            const double energy = world.energy();
            p.energy_rise_pct = std::max(p.energy_rise_pct, 100 * (energy - frame_energy) / start);
            frame_energy = energy;
        }
    }
    p.overlap_pct = 100 * depth / 0.4;
    for (const BodyState& s : world.bodies()) {
        p.fastest = std::max(p.fastest, std::hypot(s.velocity.x, s.velocity.y));
    }
    if (world.failure()) p.fastest = HUGE_VAL;
    return p;
}

}  // namespace

int main() {
    bench::ResultsFile results(
        "heavy_light_bench", {"solver", "mass_ratio", "rest_overlap_pct", "squeeze_overlap_pct",
                              "pile_median_overlap_pct", "pile_worst_overlap_pct",
                              "pile_energy_rise_pct", "pile_fastest_m_s"});
    std::printf("%-9s %7s %8s %10s %12s %11s %12s %13s\n", "solver", "ratio", "rest %",
                "squeeze %", "pile median", "pile worst", "pile rise %", "pile fastest");
    for (const bool manifold : {false, true}) {
        for (const double ratio : {10.0, 1e2, 1e3, 1e4, 1e5, 1e6}) {
            const std::string solver = manifold ? "manifold" : "disc";
            const double r = rest(ratio, manifold), s = squeeze(ratio, manifold);
            std::vector<double> overlaps;
            Pile worst;
            for (int seed = 1; seed <= 9; ++seed) {
                const Pile p = pile(ratio, manifold, seed);
                overlaps.push_back(p.overlap_pct);
                worst.energy_rise_pct = std::max(worst.energy_rise_pct, p.energy_rise_pct);
                worst.fastest = std::max(worst.fastest, p.fastest);
            }
            std::sort(overlaps.begin(), overlaps.end());
            const double median = overlaps[overlaps.size() / 2];
            std::printf("%-9s %7.0e %8.3f %10.3f %12.1f %11.1f %12.2f %13.3g\n", solver.c_str(),
                        ratio, r, s, median, overlaps.back(), worst.energy_rise_pct,
                        worst.fastest);
            results.append({solver, bench::csv_number(ratio, 0), bench::csv_number(r, 4),
                            bench::csv_number(s, 4), bench::csv_number(median, 2),
                            bench::csv_number(overlaps.back(), 2),
                            bench::csv_number(worst.energy_rise_pct, 3),
                            bench::csv_number(worst.fastest, 3)});
        }
    }
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
}

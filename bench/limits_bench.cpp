// limits_bench: what a scene of mass ratio x speed gives, for discs (the disc solver) and
// boxes (the manifold solver): docs/physics.md's "Limits" table. 64 bodies (discs of r = 0.4 m,
// or 0.8 m square boxes) on a grid in a closed 10 m box, every other one heavy, thrown in random
// directions at `radii_per_step` times 0.4 m per step; e = 0.5, mu = 0.5, g = 9.81, 480 Hz,
// 2 s. Per case: the deepest overlap between two bodies after any step (% of 0.4 m), the
// largest rise of the total energy between 60 fps frames (% of the start), how many bodies end
// outside the box, whether the state stopped being finite, and the CPU time.
// Appends to bench/results/limits_bench.csv; `limits_bench discs` or `boxes` runs one half.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench_results.hpp"
#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "scenes.hpp"

namespace {

using namespace discreel;
using namespace discreel::physics;

struct Case {
    double overlap_pct = 0;
    double energy_rise_pct = 0;
    int outside = 0;
    bool failed = false;
    double cpu_s = 0;
};

Case run(bool boxes, double ratio, double radii_per_step) {
    constexpr double r = 0.4, side = 10, rate = 480;
    WorldDef def;
    def.rate = static_cast<int>(rate);
    WallDef wall;
    wall.shape = WallDef::Shape::box;
    wall.a = {0, 0};
    wall.b = {side, side};
    wall.restitution = 0.5;
    wall.friction = 0.5;
    def.walls.push_back(wall);
    testing::Rng rng(7);  // the scenes' generator, as in tests/physics/extremes_test.cpp
    const double speed = radii_per_step * r * rate;
    for (int k = 0; k < 64; ++k) {
        const double angle = rng.uniform(0, 2 * 3.141592653589793);
        BodyDef d;
        d.position = {(1 + k % 8) * 1.1, (1 + k / 8) * 1.1};
        d.velocity = {speed * std::cos(angle), speed * std::sin(angle)};
        d.radius = r;
        d.mass = k % 2 ? ratio : 1.0;
        d.restitution = 0.5;
        d.friction = 0.5;
        if (boxes) {
            d.shape = *box_shape(2 * r, 2 * r);
            d.radius = bounding_radius(*d.shape);
        }
        def.bodies.push_back(d);
    }
    const auto begin = std::chrono::steady_clock::now();
    World world(def);
    Case c;
    const double start = world.energy();
    double frame_energy = start;
    const int steps = static_cast<int>(2 * rate), per_frame = static_cast<int>(rate / 60);
    for (int k = 0; k < steps && !world.failure(); ++k) {
        world.step();
        c.overlap_pct = std::max(c.overlap_pct, 100 * world.stats().max_overlap / r);
        if (k % per_frame == per_frame - 1) {
            const double energy = world.energy();
            c.energy_rise_pct = std::max(c.energy_rise_pct, 100 * (energy - frame_energy) / start);
            frame_energy = energy;
        }
    }
    c.failed = world.failure().has_value();
    for (const BodyState& s : world.bodies()) {
        const bool in = s.position.x > 0 && s.position.x < side && s.position.y > 0 &&
                        s.position.y < side;
        c.outside += in ? 0 : 1;
    }
    c.cpu_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return c;
}

}  // namespace

int main(int argc, char** argv) {
    // limits_bench [discs|boxes]: one half of the table (both by default).
    const std::string only = argc > 1 ? argv[1] : "";
    bench::ResultsFile results("limits_bench",
                               {"bodies", "mass_ratio", "radii_per_step", "overlap_pct",
                                "energy_rise_pct", "outside", "failed", "cpu_s"});
    std::printf("%-6s %8s %8s %12s %12s %8s %7s %8s\n", "bodies", "ratio", "r/step", "overlap %",
                "energy +%", "outside", "failed", "cpu s");
    for (const bool boxes : {false, true}) {
        if (!only.empty() && only != (boxes ? "boxes" : "discs")) continue;
        for (const double ratio : {1.0, 10.0, 1e2, 1e3, 1e4, 1e6}) {
            for (const double rps : {0.01, 0.1, 1.0, 3.0, 10.0, 30.0, 100.0}) {
                const Case c = run(boxes, ratio, rps);
                const std::string bodies = boxes ? "boxes" : "discs";
                std::printf("%-6s %8.0e %8g %12.3f %12.4f %8d %7s %8.2f\n", bodies.c_str(), ratio,
                            rps, c.overlap_pct, c.energy_rise_pct, c.outside,
                            c.failed ? "yes" : "no", c.cpu_s);
                std::fflush(stdout);
                results.append({bodies, bench::csv_number(ratio, 0), bench::csv_number(rps, 2),
                                bench::csv_number(c.overlap_pct, 3),
                                bench::csv_number(c.energy_rise_pct, 4), std::to_string(c.outside),
                                c.failed ? "1" : "0", bench::csv_number(c.cpu_s, 2)});
            }
        }
    }
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
}

// joints_bench: what joints cost, on Box2D v3's joint_grid (../shared/FIELD_NOTES.md: 100 x 100
// discs of radius 0.4, 1 m apart, each pinned to its right and lower neighbours, 19 800 pins,
// the top row hanging from 7 static discs; Box2D v3 at 60 Hz x 4 substeps: 466 ms per simulated
// second on this machine class) and a 200-link chain of capsules dropped from level, pinned to
// the world at one end. For each: milliseconds of thread CPU time per simulated second, and the
// widest gap between a pin's two anchors over the run (m), and at the end. Appends to
// bench/results/joints_bench.csv (bench_results.hpp). See docs/physics.md, "Joints".
//
//   joints_bench [seconds [grid side]]   default: 2 s, a 100 x 100 grid
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench_results.hpp"
#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"

namespace {

using discreel::Vec2;
using namespace discreel::physics;

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

JointDef pin(std::optional<std::size_t> a, std::size_t b, Vec2 at) {
    JointDef j;
    j.kind = JointDef::Kind::revolute;
    j.a = a;
    j.b = b;
    j.anchor_a = j.anchor_b = at;
    return j;
}

// Box2D's joint_grid: column i, row j at (i, -j); the top row's columns 0, 16, ..., 96 static.
WorldDef grid(int side) {
    WorldDef def;
    def.gravity = {0, -10};
    def.sleep = false;
    const auto index = [side](int i, int j) { return static_cast<std::size_t>(j * side + i); };
    for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
            BodyDef b;
            b.position = {static_cast<double>(i), -static_cast<double>(j)};
            b.radius = 0.4;
            b.mass = 1;
            b.is_static = j == 0 && i % 16 == 0;
            def.bodies.push_back(b);
        }
    }
    for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
            if (i + 1 < side) {
                def.joints.push_back(pin(index(i, j), index(i + 1, j), {i + 0.5, -j * 1.0}));
            }
            if (j + 1 < side) {
                def.joints.push_back(pin(index(i, j), index(i, j + 1), {i * 1.0, -j - 0.5}));
            }
        }
    }
    return def;
}

// n capsules of 0.25 m between pins, level at y = 60, pinned to the world at x = 0.
WorldDef chain(int n) {
    WorldDef def;
    def.sleep = false;
    const Shape capsule = capsule_shape(0.25, 0.05).value();
    for (int i = 0; i < n; ++i) {
        BodyDef b;
        b.shape = capsule;
        b.position = {(i + 0.5) * 0.25, 60};
        b.radius = bounding_radius(capsule);
        b.mass = shape_mass(capsule, 20).mass;
        def.bodies.push_back(b);
        def.joints.push_back(pin(i == 0 ? std::nullopt : std::optional<std::size_t>(i - 1),
                                 static_cast<std::size_t>(i), {i * 0.25, 60}));
    }
    return def;
}

double widest_gap(const World& world) {
    double widest = 0;
    for (const JointState& s : world.joints()) {
        widest = std::max(widest, std::hypot(s.anchor_a.x - s.anchor_b.x,
                                             s.anchor_a.y - s.anchor_b.y));
    }
    return widest;
}

}  // namespace

int main(int argc, char** argv) {
    const double seconds = argc > 1 ? std::atof(argv[1]) : 2.0;
    const int side = argc > 2 ? std::atoi(argv[2]) : 100;
    if (!(seconds > 0) || side < 2) {
        std::fprintf(stderr, "usage: joints_bench [seconds [grid side]]\n");
        return 2;
    }
    discreel::bench::ResultsFile results(
        "joints_bench", {"scene", "bodies", "joints", "rate", "seconds", "cpu_ms_per_sim_s",
                         "widest_gap_m", "gap_at_end_m"});
    std::printf("%-8s %7s %7s %5s %10s %12s %12s\n", "scene", "bodies", "joints", "rate",
                "ms/sim s", "widest gap m", "gap at end m");
    const auto run = [&](const char* name, const WorldDef& def) {
        World world(def);
        double widest = 0, stepping = 0;
        // The gap is read every 1/60 s, as a frame would show it, outside the time.
        const int per_frame = std::max(1, world.rate() / 60);
        while (world.time() < seconds) {
            const double start = thread_seconds();
            for (int k = 0; k < per_frame; ++k) world.step();
            stepping += thread_seconds() - start;
            widest = std::max(widest, widest_gap(world));
        }
        const double ms = 1e3 * stepping / world.time();
        const double end = widest_gap(world);
        std::printf("%-8s %7zu %7zu %5d %10.1f %12.2e %12.2e\n", name, def.bodies.size(),
                    def.joints.size(), world.rate(), ms, widest, end);
        results.append({name, std::to_string(def.bodies.size()), std::to_string(def.joints.size()),
                        std::to_string(world.rate()), discreel::bench::csv_number(seconds, 2),
                        discreel::bench::csv_number(ms, 1), discreel::bench::csv_number(widest, 6),
                        discreel::bench::csv_number(end, 6)});
    };
    run("chain", chain(200));
    run("grid", grid(side));
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}

// body_bench: the manifold solver's cost and accuracy on the scenes Box2D v3 is measured on
// (../shared/FIELD_NOTES.md): a 20-box stack with 1 mm gaps, the 20-row pyramid (210 boxes) and
// 1 000 random convex polygons dropped from up to 24 m into a 12 m box (placed 0.52 m apart, so
// none overlap at the start, as `validate` requires); and physics_bench's 1 000-disc pile as
// circle shapes ("circles": what discs would cost through this solver). For each, at the
// physics rates asked for: milliseconds of thread CPU time per simulated second; for the stack
// and the pyramid the largest sag below and drift beside each box's place (its start, gaps
// closed) and the fastest box, at the end; for the piles the deepest overlap in % of the
// smaller body's inscribed radius and the largest rise of energy between two 60 fps frames, in
// % of the start. Appends to bench/results/body_bench.csv (bench_results.hpp). Each scene runs
// awake (`sleep` off, as Box2D's figures in FIELD_NOTES were measured) and as scenes run by
// default, islands at rest asleep (rows named `<scene>/sleep`). See docs/physics.md;
// box2d_bench times Box2D v3 on the same scenes.
//
//   body_bench [seconds [rate...]]   default: 5 s at 480 Hz, the default physics.rate (a lower
//                                    rate takes substeps of at most 1/480 s: the same work)
//   DISCREEL_SEED=s                  another layout of the polygons (default 12345): the pile is
//                                    chaotic, its deepest overlap differs by seed
//   DISCREEL_STAGES=1                also where each scene's time went, by stage
//                                    (stage_profile.hpp)
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "bench_results.hpp"
#include "pile_scene.hpp"
#include "splitmix.hpp"
#include "stage_profile.hpp"
#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"

namespace {

using namespace discreel;
using namespace discreel::physics;

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

BodyDef box_at(double x, double y, double friction) {
    BodyDef d;
    d.shape = *box_shape(1, 1);
    d.position = {x, y};
    d.mass = 1;
    d.radius = bounding_radius(*d.shape);
    d.restitution = 0;
    d.friction = friction;
    return d;
}

WorldDef floor_world(int rate, double friction) {
    WorldDef def;
    def.rate = rate;
    WallDef floor;
    floor.shape = WallDef::Shape::box;
    floor.a = {-40, 0};
    floor.b = {40, 80};
    floor.restitution = 0;
    floor.friction = friction;
    def.walls.push_back(floor);
    return def;
}

// 1 mm between the floor and the first box and between boxes: they land on each other.
WorldDef stack(int rate) {
    WorldDef def = floor_world(rate, 0.6);
    for (int i = 0; i < 20; ++i) def.bodies.push_back(box_at(0, 0.501 + 1.001 * i, 0.6));
    return def;
}

WorldDef pyramid(int rate) {
    WorldDef def = floor_world(rate, 0.6);
    for (int row = 0; row < 20; ++row) {
        const int n = 20 - row;
        for (int i = 0; i < n; ++i) def.bodies.push_back(box_at(i - (n - 1) / 2.0, 0.5 + row, 0.6));
    }
    return def;
}

// 1 000 convex polygons of 3..8 sides, circumradius 0.1..0.25 m, on a grid 0.52 m apart (23
// across, 44 high, up to 24 m) in a 12 m wide box: they fall, land and pile up.
WorldDef polygons(int rate) {
    WorldDef def;
    def.rate = rate;
    WallDef box;
    box.shape = WallDef::Shape::box;
    box.a = {0, 0};
    box.b = {12, 30};
    box.restitution = 0.3;
    box.friction = 0.4;
    def.walls.push_back(box);
    const char* seed = std::getenv("DISCREEL_SEED");
    std::uint64_t state = seed != nullptr ? std::strtoull(seed, nullptr, 10) : 12345;
    const auto uniform = [&](double lo, double hi) { return bench::uniform(state, lo, hi); };
    for (int k = 0; k < 1000; ++k) {
        const int sides = 3 + static_cast<int>(uniform(0, 6));
        const double size = uniform(0.1, 0.25);
        std::vector<Vec2> points;
        for (int i = 0; i < sides; ++i) {
            const double a = 2 * std::numbers::pi * (i + uniform(-0.3, 0.3)) / sides;
            points.push_back({size * std::cos(a), size * std::sin(a)});
        }
        BodyDef d;
        d.shape = polygon_shape(points)->shape;
        d.position = {0.3 + 0.52 * (k % 23), 1 + 0.52 * (k / 23)};
        d.angle = uniform(0, 6.28);
        d.velocity = {uniform(-1, 1), uniform(-1, 1)};
        d.mass = shape_mass(*d.shape, 1).mass;
        d.radius = bounding_radius(*d.shape);
        d.restitution = 0.3;
        d.friction = 0.4;
        def.bodies.push_back(d);
    }
    return def;
}

// physics_bench's 1 000-disc pile with each disc a circle shape: through the manifold solver,
// with its own iterations. Beside physics_bench's figure, what discs cost through the manifold
// solver.
WorldDef circles(int rate) {
    bench::PileSettings settings;
    settings.rate = rate;
    settings.iterations = 0;
    settings.circles = true;
    return bench::pile(1000, settings);
}

struct Result {
    double ms_per_second = 0;
    // Stack and pyramid: against each box's place (its start, less the gaps below it).
    double sag_mm = std::nan(""), drift_mm = std::nan(""), fastest_mm_s = std::nan("");
    // Polygons: % of the smaller body's inscribed radius, % of the starting energy.
    double overlap_pct = std::nan(""), energy_rise_pct = std::nan("");
    StepProfile stages;   // where the time went (stage_profile.hpp)
};

// The radius of the largest circle about the centroid inside the shape, metres.
double inscribed_radius(const Shape& shape) {
    const std::size_t n = shape.vertices.size();
    if (n < 3) return shape.radius;   // a circle or a capsule
    double inner = HUGE_VAL;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = shape.vertices[i], b = shape.vertices[(i + 1) % n];
        const double length = std::hypot(b.x - a.x, b.y - a.y);
        inner = std::min(inner, std::abs(a.x * b.y - a.y * b.x) / length);
    }
    return inner + shape.radius;
}

// The deepest overlap of any two bodies, in % of the smaller one's inscribed radius: every
// pair whose bounding circles meet, by the shapes' exact separation.
double deepest_overlap_pct(const WorldDef& def, std::span<const BodyState> now,
                           const std::vector<double>& inner) {
    double deepest = 0;
    for (std::size_t i = 0; i < now.size(); ++i) {
        for (std::size_t j = i + 1; j < now.size(); ++j) {
            const double reach = def.bodies[i].radius + def.bodies[j].radius;
            const double dx = now[j].position.x - now[i].position.x;
            const double dy = now[j].position.y - now[i].position.y;
            if (dx * dx + dy * dy >= reach * reach) continue;
            const double s = separation(*def.bodies[i].shape, now[i].position, now[i].angle,
                                        *def.bodies[j].shape, now[j].position, now[j].angle);
            if (s < 0) deepest = std::max(deepest, -s / std::min(inner[i], inner[j]));
        }
    }
    return 100 * deepest;
}

Result run(WorldDef def, double seconds, bool pile) {
    def.profile = bench::stages_wanted();
    World world(def);
    const auto steps = static_cast<int>(std::lround(seconds * def.rate));
    Result r;
    if (!pile) {
        const double start = thread_seconds();
        for (int k = 0; k < steps; ++k) world.step();
        r.ms_per_second = 1000 * (thread_seconds() - start) / seconds;
        r.sag_mm = r.drift_mm = r.fastest_mm_s = 0;
        for (std::size_t i = 0; i < def.bodies.size(); ++i) {
            const BodyState& s = world.bodies()[i];
            // Each gap below a box closes: a stack's 1 mm gaps, none in the pyramid.
            const double gaps = def.bodies[i].position.y - std::floor(def.bodies[i].position.y) - 0.5;
            const double place = def.bodies[i].position.y - gaps;
            r.sag_mm = std::max(r.sag_mm, 1000 * (place - s.position.y));
            r.drift_mm = std::max(r.drift_mm, 1000 * std::abs(s.position.x - def.bodies[i].position.x));
            r.fastest_mm_s = std::max(r.fastest_mm_s, 1000 * std::hypot(s.velocity.x, s.velocity.y));
        }
        r.stages = world.profile();
        return r;
    }
    // The pile: timed apart from its measures, taken every 60 fps frame.
    std::vector<double> inner;
    for (const BodyDef& d : def.bodies) inner.push_back(inscribed_radius(*d.shape));
    const double start_energy = world.energy();
    double before = start_energy, timed = 0;
    r.overlap_pct = r.energy_rise_pct = 0;
    const int per_frame = def.rate / 60;
    for (int k = 0; k < steps; k += per_frame) {
        const double start = thread_seconds();
        for (int j = 0; j < per_frame && k + j < steps; ++j) world.step();
        timed += thread_seconds() - start;
        const double energy = world.energy();
        r.energy_rise_pct = std::max(r.energy_rise_pct, 100 * (energy - before) / std::abs(start_energy));
        before = energy;
        r.overlap_pct = std::max(r.overlap_pct, deepest_overlap_pct(def, world.bodies(), inner));
    }
    r.ms_per_second = 1000 * timed / seconds;
    r.stages = world.profile();
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    const double seconds = argc > 1 ? std::atof(argv[1]) : 5.0;
    std::vector<int> rates;
    for (int i = 2; i < argc; ++i) rates.push_back(std::atoi(argv[i]));
    if (rates.empty()) rates = {480};
    bench::ResultsFile results("body_bench",
                               {"scene", "bodies", "rate", "simulated_s", "ms_per_simulated_s",
                                "sag_mm", "drift_mm", "fastest_mm_s", "overlap_pct",
                                "energy_rise_pct"});
    std::printf("%-15s %6s %5s %10s %8s %8s %10s %10s %10s\n", "scene", "bodies", "rate",
                "ms/sim s", "sag mm", "drift mm", "fast mm/s", "overlap %", "rise %");
    const auto field = [](double v, int digits) {
        return std::isnan(v) ? std::string() : bench::csv_number(v, digits);
    };
    struct Run {
        std::string scene;
        bool sleep;
    };
    std::vector<Run> runs;
    for (const std::string scene : {"stack", "pyramid", "polygons", "circles"}) {
        runs.push_back({scene, false});
        runs.push_back({scene, true});
    }
    struct Profiled {
        std::string scene;
        std::size_t bodies;
        int rate;
        StepProfile stages;
    };
    std::vector<Profiled> profiled;
    for (const int rate : rates) {
        for (const Run& run_of : runs) {
            WorldDef def = run_of.scene == "stack"     ? stack(rate)
                           : run_of.scene == "pyramid" ? pyramid(rate)
                           : run_of.scene == "circles" ? circles(rate)
                                                       : polygons(rate);
            def.sleep = run_of.sleep;
            std::string name = run_of.sleep ? run_of.scene + "/sleep" : run_of.scene;
            // Rows of another layout say which (the CSV has no seed column).
            if (run_of.scene == "polygons" && std::getenv("DISCREEL_SEED") != nullptr) {
                name += std::string("/seed=") + std::getenv("DISCREEL_SEED");
            }
            const Result r =
                run(def, seconds, run_of.scene == "polygons" || run_of.scene == "circles");
            std::printf("%-15s %6zu %5d %10.1f %8.2f %8.2f %10.3f %10.2f %10.3f\n", name.c_str(),
                        def.bodies.size(), rate, r.ms_per_second, r.sag_mm, r.drift_mm,
                        r.fastest_mm_s, r.overlap_pct, r.energy_rise_pct);
            results.append({name, std::to_string(def.bodies.size()), std::to_string(rate),
                            bench::csv_number(seconds, 1), bench::csv_number(r.ms_per_second, 1),
                            field(r.sag_mm, 3), field(r.drift_mm, 3), field(r.fastest_mm_s, 3),
                            field(r.overlap_pct, 2), field(r.energy_rise_pct, 3)});
            profiled.push_back({name, def.bodies.size(), rate, r.stages});
        }
    }
    if (bench::stages_wanted()) {
        bench::StageTable stages;
        stages.print_header();
        for (const Profiled& p : profiled) {
            stages.add("body_bench", p.scene, p.bodies, p.rate, seconds, p.stages);
        }
    }
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}

// body_bench: the manifold solver's cost and accuracy on the scenes Box2D v3 is measured on
// (../shared/FIELD_NOTES.md): a 20-box stack, the 20-row pyramid (210 boxes) and a pile of
// 1 000 random convex polygons falling into a box. For each, at the physics rates asked for,
// milliseconds of thread CPU time per simulated second, and for the stack and the pyramid the
// largest sag below and drift beside each box's ideal place after 5 s. Appends to
// bench/results/body_bench.csv (bench_results.hpp). See docs/performance.md.
//
//   body_bench [rate...]      default: 480, the default physics.rate (a lower rate takes
//                             substeps of at most 1/480 s: the same work)
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "bench_results.hpp"
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

DiscDef box_at(double x, double y, double friction) {
    DiscDef d;
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

WorldDef stack(int rate) {
    WorldDef def = floor_world(rate, 0.6);
    for (int i = 0; i < 20; ++i) def.discs.push_back(box_at(0, 0.5 + i, 0.6));
    return def;
}

WorldDef pyramid(int rate) {
    WorldDef def = floor_world(rate, 0.6);
    for (int row = 0; row < 20; ++row) {
        const int n = 20 - row;
        for (int i = 0; i < n; ++i) def.discs.push_back(box_at(i - (n - 1) / 2.0, 0.5 + row, 0.6));
    }
    return def;
}

// 1 000 convex polygons of 3..8 sides, circumradius 0.1..0.25 m, dropped on a 40 x 25 grid
// into a 12 m wide box: they land and pile up within the 5 simulated seconds.
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
    std::uint64_t state = 12345;
    const auto uniform = [&](double lo, double hi) {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
    };
    for (int k = 0; k < 1000; ++k) {
        const int sides = 3 + static_cast<int>(uniform(0, 6));
        const double size = uniform(0.1, 0.25);
        std::vector<Vec2> points;
        for (int i = 0; i < sides; ++i) {
            const double a = 2 * std::numbers::pi * (i + uniform(-0.3, 0.3)) / sides;
            points.push_back({size * std::cos(a), size * std::sin(a)});
        }
        DiscDef d;
        d.shape = polygon_shape(points)->shape;
        d.position = {0.3 + 0.29 * (k % 40), 1 + 0.6 * (k / 40)};
        d.angle = uniform(0, 6.28);
        d.velocity = {uniform(-1, 1), uniform(-1, 1)};
        d.mass = shape_mass(*d.shape, 1).mass;
        d.radius = bounding_radius(*d.shape);
        d.restitution = 0.3;
        d.friction = 0.4;
        def.discs.push_back(d);
    }
    return def;
}

struct Result {
    double ms_per_second = 0;
    double sag_mm = 0, drift_mm = 0;   // against the starting places; NaN for the pile
};

Result run(const WorldDef& def, double seconds, bool measure_places) {
    World world(def);
    const auto steps = static_cast<int>(std::lround(seconds * def.rate));
    const double start = thread_seconds();
    for (int k = 0; k < steps; ++k) world.step();
    Result r;
    r.ms_per_second = 1000 * (thread_seconds() - start) / seconds;
    r.sag_mm = r.drift_mm = std::nan("");
    if (measure_places) {
        r.sag_mm = r.drift_mm = 0;
        for (std::size_t i = 0; i < def.discs.size(); ++i) {
            const Vec2 p = world.discs()[i].position;
            r.sag_mm = std::max(r.sag_mm, 1000 * (def.discs[i].position.y - p.y));
            r.drift_mm = std::max(r.drift_mm, 1000 * std::abs(p.x - def.discs[i].position.x));
        }
    }
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> rates;
    for (int i = 1; i < argc; ++i) rates.push_back(std::atoi(argv[i]));
    if (rates.empty()) rates = {480};
    bench::ResultsFile results("body_bench", {"scene", "bodies", "rate", "simulated_s",
                                              "ms_per_simulated_s", "sag_mm", "drift_mm"});
    std::printf("%-10s %6s %5s %12s %8s %8s\n", "scene", "bodies", "rate", "ms/sim s", "sag mm",
                "drift mm");
    constexpr double seconds = 5.0;
    for (const int rate : rates) {
        for (const std::string name : {"stack", "pyramid", "polygons"}) {
            const WorldDef def = name == "stack" ? stack(rate)
                                 : name == "pyramid" ? pyramid(rate)
                                                     : polygons(rate);
            const Result r = run(def, seconds, name != "polygons");
            std::printf("%-10s %6zu %5d %12.1f %8.2f %8.2f\n", name.c_str(), def.discs.size(),
                        rate, r.ms_per_second, r.sag_mm, r.drift_mm);
            results.append({name, std::to_string(def.discs.size()), std::to_string(rate),
                            bench::csv_number(seconds, 1), bench::csv_number(r.ms_per_second, 1),
                            std::isnan(r.sag_mm) ? "" : bench::csv_number(r.sag_mm, 3),
                            std::isnan(r.drift_mm) ? "" : bench::csv_number(r.drift_mm, 3)});
        }
    }
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}

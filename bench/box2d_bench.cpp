// box2d_bench: Box2D v3 on the scenes of body_bench and physics_bench, built from the same
// layouts, so that the two can be timed on one machine in the same minute. Box2D is not a
// Debian package in its v3 form and discreel vendors nothing: this bench is built only when
// DISCREEL_BOX2D_SOURCE names a Box2D v3 checkout (docs/physics-speed.md, "Box2D side by
// side"). 60 Hz steps, one thread, sleep off, as FIELD_NOTES.md measured it.
//
//   box2d_bench [seconds [substeps...]]   default: 5 s at 4 and 16 substeps
//   DISCREEL_SEED=s                       another layout of the polygons (default 12345)
//   DISCREEL_BOX2D_HERTZ=f                contact stiffness, Hz (Box2D's default 30; Box2D caps
//                                         it at 1/8 of the substep rate): 120 at 16 substeps
//                                         sags the pyramid about as little as body_bench's
//
// Per scene: milliseconds of thread CPU time per simulated second; for the stack and the
// pyramid the sag below and drift beside each box's place at the end (as body_bench); for the
// polygons the deepest overlap of touching pairs after each step, by Box2D's own manifolds,
// in % of the smaller polygon's inscribed radius, and the largest rise of energy between
// steps in % of the start; for the 1 000-disc pile, time only. Appends to
// bench/results/box2d_bench.csv.
#include <box2d/box2d.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "bench_results.hpp"
#include "splitmix.hpp"

namespace {

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

struct Scene {
    b2WorldId world{};
    std::vector<b2BodyId> bodies;
    std::vector<b2Vec2> start;          // where each body began
    std::vector<float> inner;           // polygons: inscribed radius about the centroid, m
};

b2WorldId make_world() {
    b2WorldDef def = b2DefaultWorldDef();
    def.enableSleep = false;
    def.gravity = {0, -9.8f};
    def.workerCount = 1;
    if (const char* hertz = std::getenv("DISCREEL_BOX2D_HERTZ")) {
        def.contactHertz = std::strtof(hertz, nullptr);
    }
    return b2CreateWorld(&def);
}

// A static box spanning [x0, x1] x [y0, y1].
void add_slab(b2WorldId world, float x0, float y0, float x1, float y1, float friction,
              float restitution) {
    b2BodyDef def = b2DefaultBodyDef();
    const b2BodyId ground = b2CreateBody(world, &def);
    b2ShapeDef shape = b2DefaultShapeDef();
    shape.material.friction = friction;
    shape.material.restitution = restitution;
    const b2Polygon slab = b2MakeOffsetBox(0.5f * (x1 - x0), 0.5f * (y1 - y0),
                                           {0.5f * (x0 + x1), 0.5f * (y0 + y1)}, b2Rot_identity);
    b2CreatePolygonShape(ground, &shape, &slab);
}

b2BodyId add_body(Scene& s, b2Vec2 at, float angle, b2Vec2 velocity) {
    b2BodyDef def = b2DefaultBodyDef();
    def.type = b2_dynamicBody;
    def.position = at;
    def.rotation = b2MakeRot(angle);
    def.linearVelocity = velocity;
    // The user data is the body's place in s.bodies, plus one (0: a wall).
    def.userData = reinterpret_cast<void*>(static_cast<std::uintptr_t>(s.bodies.size() + 1));
    const b2BodyId body = b2CreateBody(s.world, &def);
    s.bodies.push_back(body);
    s.start.push_back(at);
    return body;
}

// body_bench's floor (a wall box from (-40, 0) to (40, 80): its floor is y = 0) with unit
// boxes of density 1 (body_bench's mass 1), friction 0.6, no restitution.
Scene boxes(bool pyramid) {
    Scene s;
    s.world = make_world();
    add_slab(s.world, -40, -1, 40, 0, 0.6f, 0);
    const b2Polygon box = b2MakeBox(0.5f, 0.5f);
    const auto add = [&](double x, double y) {
        const b2BodyId body = add_body(s, {static_cast<float>(x), static_cast<float>(y)}, 0, {0, 0});
        b2ShapeDef shape = b2DefaultShapeDef();
        shape.material.friction = 0.6f;
        shape.density = 1;
        b2CreatePolygonShape(body, &shape, &box);
    };
    if (!pyramid) {
        for (int i = 0; i < 20; ++i) add(0, 0.501 + 1.001 * i);
        return s;
    }
    for (int row = 0; row < 20; ++row) {
        const int n = 20 - row;
        for (int i = 0; i < n; ++i) add(i - (n - 1) / 2.0, 0.5 + row);
    }
    return s;
}

// body_bench's polygons, drawn from the same generator in the same order; the wall box
// (0, 0)-(12, 30) as four slabs.
Scene polygons() {
    Scene s;
    s.world = make_world();
    add_slab(s.world, -1, -1, 13, 0, 0.4f, 0.3f);
    add_slab(s.world, -1, 30, 13, 31, 0.4f, 0.3f);
    add_slab(s.world, -1, 0, 0, 30, 0.4f, 0.3f);
    add_slab(s.world, 12, 0, 13, 30, 0.4f, 0.3f);
    const char* seed = std::getenv("DISCREEL_SEED");
    std::uint64_t state = seed != nullptr ? std::strtoull(seed, nullptr, 10) : 12345;
    const auto uniform = [&](double lo, double hi) {
        return discreel::bench::uniform(state, lo, hi);
    };
    for (int k = 0; k < 1000; ++k) {
        const int sides = 3 + static_cast<int>(uniform(0, 6));
        const double size = uniform(0.1, 0.25);
        b2Vec2 points[8];
        for (int i = 0; i < sides; ++i) {
            const double a = 2 * std::numbers::pi * (i + uniform(-0.3, 0.3)) / sides;
            points[i] = {static_cast<float>(size * std::cos(a)), static_cast<float>(size * std::sin(a))};
        }
        const b2Hull hull = b2ComputeHull(points, sides);
        const b2Polygon polygon = b2MakePolygon(&hull, 0);
        const b2Vec2 at = {static_cast<float>(0.3 + 0.52 * (k % 23)),
                           static_cast<float>(1 + 0.52 * (k / 23))};
        const auto angle = static_cast<float>(uniform(0, 6.28));
        const b2Vec2 velocity = {static_cast<float>(uniform(-1, 1)), static_cast<float>(uniform(-1, 1))};
        const b2BodyId body = add_body(s, at, angle, velocity);
        b2ShapeDef shape = b2DefaultShapeDef();
        shape.material.friction = 0.4f;
        shape.material.restitution = 0.3f;
        shape.density = 1;
        b2CreatePolygonShape(body, &shape, &polygon);
        float inner = 1e9f;
        for (int i = 0; i < polygon.count; ++i) {
            inner = std::min(inner, b2Dot(polygon.normals[i], b2Sub(polygon.vertices[i], polygon.centroid)));
        }
        s.inner.push_back(inner);
    }
    return s;
}

// physics_bench's pile of 1 000 discs (r = 0.5, density 1, e = 0.5, mu = 0.6) in its box.
Scene discs() {
    Scene s;
    s.world = make_world();
    const int n = 1000;
    const double spacing = 1.4;
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const auto side = static_cast<float>(spacing * columns);
    add_slab(s.world, -1, -1, side + 1, 0, 0.6f, 0.5f);
    add_slab(s.world, -1, side, side + 1, side + 1, 0.6f, 0.5f);
    add_slab(s.world, -1, 0, 0, side, 0.6f, 0.5f);
    add_slab(s.world, side, 0, side + 1, side, 0.6f, 0.5f);
    std::uint64_t seed = 12345;
    const auto uniform = [&](double lo, double hi) {
        return discreel::bench::uniform(seed, lo, hi);
    };
    const b2Circle circle = {{0, 0}, 0.5f};
    for (int k = 0; k < n; ++k) {
        const b2Vec2 at = {static_cast<float>(spacing * (0.5 + k % columns)),
                           static_cast<float>(spacing * (0.5 + k / columns))};
        const b2Vec2 velocity = {static_cast<float>(uniform(-0.5, 0.5)),
                                 static_cast<float>(uniform(-0.5, 0.5))};
        const b2BodyId body = add_body(s, at, 0, velocity);
        b2ShapeDef shape = b2DefaultShapeDef();
        shape.material.friction = 0.6f;
        shape.material.restitution = 0.5f;
        shape.density = 1;
        b2CreateCircleShape(body, &shape, &circle);
    }
    return s;
}

struct Result {
    double ms_per_second = 0;
    double sag_mm = std::nan(""), drift_mm = std::nan("");
    double overlap_pct = std::nan(""), energy_rise_pct = std::nan("");
};

double energy(const Scene& s) {
    double e = 0;
    for (const b2BodyId b : s.bodies) {
        const double m = b2Body_GetMass(b);
        const b2Vec2 v = b2Body_GetLinearVelocity(b);
        const double w = b2Body_GetAngularVelocity(b);
        e += 0.5 * m * (v.x * v.x + v.y * v.y) + 0.5 * b2Body_GetRotationalInertia(b) * w * w +
             9.8 * m * b2Body_GetWorldCenter(b).y;
    }
    return e;
}

double deepest_overlap_pct(const Scene& s, std::vector<b2ContactData>& scratch) {
    double deepest = 0;
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        scratch.resize(static_cast<std::size_t>(b2Body_GetContactCapacity(s.bodies[i])));
        const int n = b2Body_GetContactData(s.bodies[i], scratch.data(), static_cast<int>(scratch.size()));
        for (int c = 0; c < n; ++c) {
            const b2ContactData& d = scratch[static_cast<std::size_t>(c)];
            double inner = s.inner[i];
            for (const b2ShapeId shape : {d.shapeIdA, d.shapeIdB}) {
                const auto place = reinterpret_cast<std::uintptr_t>(
                    b2Body_GetUserData(b2Shape_GetBody(shape)));
                if (place > 0) inner = std::min(inner, static_cast<double>(s.inner[place - 1]));
            }
            for (int p = 0; p < d.manifold.pointCount; ++p) {
                deepest = std::max(deepest, -d.manifold.points[p].separation / inner);
            }
        }
    }
    return 100 * deepest;
}

// What run() measures besides the time: nothing, the pile's overlap and energy after every
// step, or the boxes' sag and drift at the end.
enum class Measure { time, pile, places };

Result run(Scene s, double seconds, int substeps, Measure measure) {
    const int steps = static_cast<int>(std::lround(seconds * 60));
    Result r;
    const double start_energy = energy(s);
    double before = start_energy, timed = 0;
    std::vector<b2ContactData> scratch;
    if (measure == Measure::pile) r.overlap_pct = r.energy_rise_pct = 0;
    for (int k = 0; k < steps; ++k) {
        const double t0 = thread_seconds();
        b2World_Step(s.world, 1.0f / 60, substeps);
        timed += thread_seconds() - t0;
        if (measure != Measure::pile) continue;
        const double now = energy(s);
        r.energy_rise_pct = std::max(r.energy_rise_pct, 100 * (now - before) / std::abs(start_energy));
        before = now;
        r.overlap_pct = std::max(r.overlap_pct, deepest_overlap_pct(s, scratch));
    }
    r.ms_per_second = 1000 * timed / seconds;
    if (measure == Measure::places) {
        r.sag_mm = r.drift_mm = 0;
        for (std::size_t i = 0; i < s.bodies.size(); ++i) {
            const b2Vec2 p = b2Body_GetPosition(s.bodies[i]);
            const b2Vec2 start = s.start[i];
            // Each gap below a box closes: a stack's 1 mm gaps, none in the pyramid.
            const double gaps = start.y - std::floor(static_cast<double>(start.y)) - 0.5;
            const double place = start.y - gaps;
            r.sag_mm = std::max(r.sag_mm, 1000 * (place - p.y));
            r.drift_mm = std::max(r.drift_mm, 1000.0 * std::abs(p.x - start.x));
        }
    }
    b2DestroyWorld(s.world);
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace discreel;
    const double seconds = argc > 1 ? std::atof(argv[1]) : 5.0;
    std::vector<int> substeps;
    for (int i = 2; i < argc; ++i) substeps.push_back(std::atoi(argv[i]));
    if (substeps.empty()) substeps = {4, 16};
    bench::ResultsFile results("box2d_bench",
                               {"scene", "bodies", "substeps", "simulated_s", "ms_per_simulated_s",
                                "sag_mm", "drift_mm", "overlap_pct", "energy_rise_pct"});
    std::printf("%-10s %6s %8s %10s %8s %8s %10s %8s\n", "scene", "bodies", "substeps",
                "ms/sim s", "sag mm", "drift mm", "overlap %", "rise %");
    const auto field = [](double v, int digits) {
        return std::isnan(v) ? std::string() : bench::csv_number(v, digits);
    };
    for (const int sub : substeps) {
        for (const std::string scene : {"stack", "pyramid", "polygons", "discs"}) {
            Result r;
            std::size_t bodies = 0;
            if (scene == "stack" || scene == "pyramid") {
                bodies = scene == "stack" ? 20 : 210;
                r = run(boxes(scene == "pyramid"), seconds, sub, Measure::places);
            } else if (scene == "polygons") {
                bodies = 1000;
                r = run(polygons(), seconds, sub, Measure::pile);
            } else {
                bodies = 1000;
                r = run(discs(), seconds, sub, Measure::time);
            }
            std::string name = scene;
            if (scene == "polygons" && std::getenv("DISCREEL_SEED") != nullptr) {
                name += std::string("/seed=") + std::getenv("DISCREEL_SEED");
            }
            if (const char* hertz = std::getenv("DISCREEL_BOX2D_HERTZ")) {
                name += std::string("/hz=") + hertz;
            }
            std::printf("%-10s %6zu %8d %10.1f %8.2f %8.2f %10.2f %8.3f\n", name.c_str(), bodies,
                        sub, r.ms_per_second, r.sag_mm, r.drift_mm, r.overlap_pct,
                        r.energy_rise_pct);
            results.append({name, std::to_string(bodies), std::to_string(sub),
                            bench::csv_number(seconds, 1), bench::csv_number(r.ms_per_second, 1),
                            field(r.sag_mm, 3), field(r.drift_mm, 3), field(r.overlap_pct, 2),
                            field(r.energy_rise_pct, 3)});
        }
    }
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}

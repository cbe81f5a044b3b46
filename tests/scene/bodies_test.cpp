// `bodies:` in scene files: each shape arrives with the mass and inertia its geometry gives,
// polygons centred on their area centroid, circles as plain discs; shapes are checked for
// overlap by their outlines, not their bounding circles; `random_polygons` scatters convex
// polygons without overlap, the same for the same seed, and respawns them on schedule.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/shapes.hpp"
#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using testing::load_ok;
using testing::problems;
using testing::warnings;

TEST(Bodies, EachShapeHasTheMassAndInertiaOfItsGeometry) {
    const Scene s = load_ok(R"(
version: 1
discs:
  - {position: [0, 5], radius: 0.5}
bodies:
  - {id: crate, box: [0.8, 0.5], position: [3, 2], density: 2}
  - {polygon: [[0, 0], [3, 0], [0, 3]], position: [6, 3], mass: 4.5}
  - {capsule: {length: 1.0, radius: 0.2}, position: [9, 2]}
  - {circle: 0.3, position: [12, 4], density: 2}
)");
    ASSERT_EQ(s.bodies.size(), 5u);
    EXPECT_EQ(s.bodies[1].id, "crate");   // one numbering: discs, then bodies
    const Body& crate = s.bodies[1];
    ASSERT_TRUE(crate.shape);
    EXPECT_NEAR(crate.mass, 2 * 0.8 * 0.5, 1e-12);
    EXPECT_NEAR(crate.inertia, crate.mass * (0.64 + 0.25) / 12, 1e-12);
    EXPECT_NEAR(crate.radius, std::hypot(0.4, 0.25), 1e-12);   // the bounding radius
    // A right triangle: its centroid (1, 1) is the origin of its vertices, the body's position.
    const Body& wedge = s.bodies[2];
    ASSERT_TRUE(wedge.shape);
    EXPECT_NEAR(wedge.shape->vertices[0].x, -1, 1e-12);
    EXPECT_NEAR(wedge.shape->vertices[0].y, -1, 1e-12);
    EXPECT_EQ(wedge.position, (Vec2{6, 3}));
    EXPECT_NEAR(wedge.mass, 4.5, 1e-12);
    EXPECT_NEAR(wedge.inertia, 4.5 * (9 + 9) / 18, 1e-12);   // m (a^2 + b^2) / 18 about the centroid
    const Body& capsule = s.bodies[3];
    EXPECT_NEAR(capsule.mass, 1.0 * 0.4 + std::numbers::pi * 0.04, 1e-12);
    EXPECT_NEAR(capsule.radius, 0.7, 1e-12);
    const Body& circle = s.bodies[4];
    EXPECT_FALSE(circle.shape);   // exactly a disc
    EXPECT_NEAR(circle.radius, 0.3, 1e-12);
    EXPECT_NEAR(circle.mass, 2 * std::numbers::pi * 0.09, 1e-12);
    EXPECT_NEAR(circle.inertia, 0.5 * circle.mass * 0.09, 1e-12);
}

TEST(Bodies, TouchingBoxesLoadAndOverlappingOnesAreRefused) {
    load_ok(R"(
version: 1
bodies:
  - {box: [1, 1], position: [0, 0.5]}
  - {box: [1, 1], position: [0, 1.5]}
  - {box: [1, 1], position: [1.25, 0.5], angle: 0.78}
)");
    EXPECT_EQ(problems(R"(
version: 1
bodies:
  - {id: a, box: [1, 1], position: [0, 0.5]}
  - {id: b, box: [1, 1], position: [0, 1.4]}
)"),
              (std::vector<std::string>{
                  "s.yaml:5:5: bodies[1]: body 'b' overlaps body 'a' (line 4) by 0.1 m at t = 0"}));
}

// A capsule is a rectangle and two half discs; the inertia about its centre is theirs summed
// (the half discs' centroids lie 4 r / (3 pi) beyond the segment's ends).
TEST(Bodies, CapsuleInertiaIsTheRectangleAndTheTwoHalfDiscs) {
    const Scene s = load_ok(R"(
version: 1
bodies:
  - {capsule: {length: 1.0, radius: 0.2}, position: [0, 0], density: 3}
)");
    const double length = 1.0, r = 0.2, density = 3;
    const double rectangle = density * length * 2 * r;
    const double discs = density * std::numbers::pi * r * r;
    const double inertia = rectangle * (length * length + 4 * r * r) / 12 +
                           discs * (r * r / 2 + length * length / 4 +
                                    length * 4 * r / (3 * std::numbers::pi));
    ASSERT_EQ(s.bodies.size(), 1u);
    EXPECT_NEAR(s.bodies[0].mass, rectangle + discs, 1e-12);
    EXPECT_NEAR(s.bodies[0].inertia, inertia, 1e-12);
}

// Either winding gives the same body; a static body keeps its mass but has no inertia.
TEST(Bodies, PolygonWindingDoesNotMatterAndStaticBodiesHaveNoInertia) {
    const Scene s = load_ok(R"(
version: 1
bodies:
  - {polygon: [[0, 0], [2, 0], [2, 1], [0, 1]], position: [0, 0]}
  - {polygon: [[0, 1], [2, 1], [2, 0], [0, 0]], position: [5, 0]}
  - {box: [2, 1], position: [10, 0], static: true}
)");
    ASSERT_EQ(s.bodies.size(), 3u);
    EXPECT_NEAR(s.bodies[0].mass, 2.0, 1e-12);
    EXPECT_NEAR(s.bodies[0].inertia, 2.0 * (4 + 1) / 12, 1e-12);
    EXPECT_NEAR(s.bodies[1].mass, s.bodies[0].mass, 1e-12);
    EXPECT_NEAR(s.bodies[1].inertia, s.bodies[0].inertia, 1e-12);
    EXPECT_NEAR(s.bodies[1].radius, std::hypot(1.0, 0.5), 1e-12);
    EXPECT_TRUE(s.bodies[2].is_static);
    EXPECT_NEAR(s.bodies[2].mass, 2.0, 1e-12);
    EXPECT_EQ(s.bodies[2].inertia, 0.0);
}

// A body whose bounding circle first meets a body it is clear of is still checked against the
// later one it does overlap.
TEST(Bodies, AnOverlapBehindAClearNeighbourIsFound) {
    EXPECT_EQ(problems(R"(
version: 1
bodies:
  - {id: a, box: [1, 1], position: [0, 0.5]}
  - {id: b, box: [1, 1], position: [0, 1.5]}
  - {id: c, box: [1, 1], position: [0.5, 1.5]}
)"),
              (std::vector<std::string>{
                  "s.yaml:6:5: bodies[2]: body 'c' overlaps body 'b' (line 5) by 0.5 m at t = 0"}));
}

TEST(Bodies, RandomPolygonsScatterWithoutOverlapTheSameForTheSameSeed) {
    const std::string yaml = R"(
version: 1
video: {duration: 10}
walls:
  - box: [[0, 0], [12, 7]]
bodies:
  - random_polygons:
      count: 40
      region: [[1, 1], [11, 6]]
      sides: [3, 8]
      size: [0.2, 0.5]
      speed: [0, 2]
      angular_speed: [1, 3]
      respawn_every: 4.0
)";
    const Scene a = load_ok(yaml);
    const Scene b = load_ok(yaml);
    ASSERT_EQ(a.bodies.size(), 40u);
    EXPECT_EQ(a.bodies[0].id, "body0.0");
    EXPECT_EQ(a.bodies[39].id, "body0.39");
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        const Body& p = a.bodies[i];
        ASSERT_TRUE(p.shape);
        EXPECT_GE(p.shape->vertices.size(), 3u);
        EXPECT_LE(p.shape->vertices.size(), 8u);
        EXPECT_LE(p.radius, 0.5 + 1e-12);
        EXPECT_GE(std::abs(p.angular_velocity), 1.0);
        EXPECT_EQ(p.position, b.bodies[i].position);
        EXPECT_EQ(p.shape->vertices.size(), b.bodies[i].shape->vertices.size());
        for (std::size_t j = 0; j < i; ++j) {
            const Body& q = a.bodies[j];
            EXPECT_GE(physics::separation(*p.shape, p.position, p.angle, *q.shape, q.position,
                                          q.angle, 0.0),
                      0.0);
        }
    }
    // Respawned at 4 and 8 s (not 12: past the 10 s clip), each a new draw of 40.
    ASSERT_EQ(a.respawns.size(), 2u);
    EXPECT_EQ(a.respawns[0].at, 4.0);
    EXPECT_EQ(a.respawns[1].at, 8.0);
    EXPECT_EQ(a.respawns[0].first, 0u);
    ASSERT_EQ(a.respawns[0].bodies.size(), 40u);
    EXPECT_EQ(a.respawns[0].bodies[7].id, "body0.7");
    EXPECT_NE(a.respawns[0].bodies[7].position, a.bodies[7].position);
    EXPECT_EQ(a.respawns[1].bodies[7].position, b.respawns[1].bodies[7].position);
}

// The generator's `id` names its bodies, `colors` cycle, `sides` bounds the vertex count, and
// the single-body keys apply to each.
TEST(Bodies, RandomPolygonsTakeAnIdPrefixColoursSidesAndBodyKeys) {
    const Scene s = load_ok(R"(
version: 1
discs:
  - {position: [20, 20], radius: 0.5}
bodies:
  - {box: [1, 1], position: [20, 22]}
  - random_polygons:
      id: rock
      count: 5
      region: [[0, 0], [10, 10]]
      sides: [4, 5]
      size: [0.3, 0.4]
      colors: ["#ff0000", "#00ff00"]
    density: 2
    static: true
)");
    ASSERT_EQ(s.bodies.size(), 7u);
    for (std::size_t k = 0; k < 5; ++k) {
        const Body& p = s.bodies[2 + k];
        EXPECT_EQ(p.id, "rock." + std::to_string(k));
        EXPECT_EQ(p.color, (k % 2 == 0 ? Color{0xff, 0, 0, 0xff} : Color{0, 0xff, 0, 0xff}));
        ASSERT_TRUE(p.shape);
        EXPECT_GE(p.shape->vertices.size(), 4u);
        EXPECT_LE(p.shape->vertices.size(), 5u);
        EXPECT_TRUE(p.is_static);
        EXPECT_EQ(p.inertia, 0.0);
        EXPECT_NEAR(p.mass, 2 * physics::shape_mass(*p.shape, 1.0).area, 1e-12);
    }
    EXPECT_TRUE(s.respawns.empty());
}

// Without an id, the generator's bodies take its index in `bodies:`; respawns of several
// generators come in order of time (physics applies them in list order).
TEST(Bodies, RespawnsOfSeveralGeneratorsAreInOrderOfTime) {
    const Scene s = load_ok(R"(
version: 1
video: {duration: 10}
bodies:
  - {box: [1, 1], position: [-5, -5]}
  - random_polygons: {count: 3, region: [[0, 0], [5, 5]], size: 0.3, respawn_every: 4}
  - random_polygons: {count: 2, region: [[10, 0], [15, 5]], size: 0.3, respawn_every: 3}
)");
    ASSERT_EQ(s.bodies.size(), 6u);
    for (const Body& body : s.bodies) EXPECT_FALSE(std::signbit(body.angular_velocity)) << body.id;
    EXPECT_EQ(s.bodies[1].id, "body1.0");
    EXPECT_EQ(s.bodies[4].id, "body2.0");
    std::vector<std::pair<double, std::size_t>> schedule;
    for (const Respawn& r : s.respawns) {
        schedule.emplace_back(r.at, r.first);
        const std::size_t expected = r.first == 1 ? 3 : 2;
        ASSERT_EQ(r.bodies.size(), expected);
        EXPECT_EQ(r.bodies[0].id, s.bodies[r.first].id);
        EXPECT_EQ(r.bodies[expected - 1].id, s.bodies[r.first + expected - 1].id);
    }
    EXPECT_EQ(schedule, (std::vector<std::pair<double, std::size_t>>{
                            {3, 4}, {4, 1}, {6, 4}, {8, 1}, {9, 4}}));
}

// Every set, the first and each respawned one, keeps clear of walls; a respawned set also keeps
// clear of static bodies, those declared after its generator too.
TEST(Bodies, RandomPolygonsKeepClearOfWallsAndOfStaticBodies) {
    const Scene s = load_ok(R"(
version: 1
video: {duration: 10}
walls:
  - segment: [[0, 4], [8, 4]]
    thickness: 0.2
bodies:
  - random_polygons:
      count: 15
      region: [[0, 0], [8, 8]]
      size: 0.3
      respawn_every: 1
  - random_polygons: {count: 10, region: [[0, 0], [8, 8]], size: 0.5, static: true}
)");
    ASSERT_EQ(s.bodies.size(), 25u);
    ASSERT_EQ(s.respawns.size(), 9u);
    std::vector<std::vector<Body>> sets{s.bodies};
    for (const Respawn& r : s.respawns) {
        std::vector<Body> now = s.bodies;
        std::copy(r.bodies.begin(), r.bodies.end(),
                  now.begin() + static_cast<std::ptrdiff_t>(r.first));
        sets.push_back(now);
    }
    for (const std::vector<Body>& set : sets) {
        for (const Body& body : set) {
            EXPECT_GE(std::abs(body.position.y - 4), body.radius + 0.1 - 1e-9) << body.id;
        }
        for (std::size_t i = 0; i < 15; ++i) {
            for (std::size_t j = 15; j < 25; ++j) {
                const double gap = std::hypot(set[i].position.x - set[j].position.x,
                                              set[i].position.y - set[j].position.y);
                EXPECT_GE(gap, set[i].radius + set[j].radius - 1e-9) << set[i].id << set[j].id;
            }
        }
    }
}

// Speeds are judged where a crowd can form: three bullets fired at a wall are not one; the same
// bullets among eight resting discs are. `warnings: false` silences what remains.
TEST(Bodies, FastBodiesAreJudgedOnlyAmongACrowd) {
    const std::string bullets = R"(
version: 1
walls:
  - box: [[0, 0], [20, 10]]
discs:
  - {id: a, position: [2, 2], radius: 0.05, velocity: [400, 0]}
  - {id: b, position: [2, 5], radius: 0.05, velocity: [400, 0]}
  - {id: c, position: [2, 8], radius: 0.05, velocity: [400, 0]}
)";
    EXPECT_EQ(warnings(bullets), std::vector<std::string>{});
    const std::string crowd =
        bullets + "  - grid: {origin: [10, 1], count: [8, 1], spacing: [1, 1], radius: 0.05}\n";
    EXPECT_EQ(warnings(crowd),
              (std::vector<std::string>{
                  "s.yaml:6:55: warning: discs[0].velocity: 400 m/s: crowds of this scene's "
                  "bodies are measured to stay apart up to 240 m/s at 480 Hz (10 radii of the "
                  "smallest moving body, 'a', 0.05 m, per physics step); where several bodies "
                  "this fast meet at once they may overlap; physics.rate 800 or more keeps them "
                  "apart (docs/physics.md, Limits)",
                  "s.yaml:7:55: warning: discs[1].velocity: 400 m/s: crowds of this scene's "
                  "bodies are measured to stay apart up to 240 m/s at 480 Hz (10 radii of the "
                  "smallest moving body, 'a', 0.05 m, per physics step); where several bodies "
                  "this fast meet at once they may overlap; physics.rate 800 or more keeps them "
                  "apart (docs/physics.md, Limits)",
                  "s.yaml:8:55: warning: discs[2].velocity: 400 m/s: crowds of this scene's "
                  "bodies are measured to stay apart up to 240 m/s at 480 Hz (10 radii of the "
                  "smallest moving body, 'a', 0.05 m, per physics step); where several bodies "
                  "this fast meet at once they may overlap; physics.rate 800 or more keeps them "
                  "apart (docs/physics.md, Limits)"}));
    EXPECT_EQ(warnings(crowd + "warnings: false\n"), std::vector<std::string>{});
    EXPECT_EQ(problems(bullets + "warnings: maybe\n"),
              std::vector<std::string>{"s.yaml:9:11: warnings: expected true or false, got 'maybe'"});
}

// A respawned set is judged with the bodies alive beside it: one polygon's successors may
// differ from it in mass without a warning, but not from a body they meet. (The seeds pick
// draws whose first sets are within the crowd's range and a later respawn is not.)
TEST(Bodies, RespawnedSetsAreJudgedWithTheBodiesAliveBesideThem) {
    const Scene alone = load_ok(R"(
version: 1
video: {duration: 12}
bodies:
  - random_polygons: {count: 1, region: [[0, 0], [10, 10]], size: [0.01, 1], respawn_every: 1}
)");
    double lightest = alone.bodies[0].mass, heaviest = lightest;
    for (const Respawn& r : alone.respawns) {
        lightest = std::min(lightest, r.bodies[0].mass);
        heaviest = std::max(heaviest, r.bodies[0].mass);
    }
    EXPECT_GT(heaviest / lightest, 1000);

    EXPECT_EQ(warnings(R"(
version: 1
video: {duration: 6}
physics: {seed: 6}
bodies:
  - {id: anvil, box: [1, 1], position: [20, 20], mass: 1000}
  - random_polygons: {count: 1, region: [[0, 0], [10, 10]], size: [0.3, 1], respawn_every: 1}
)"),
              (std::vector<std::string>{
                  "s.yaml:7:5: warning: bodies[1]: after the respawn at t = 3 s, the moving "
                  "bodies differ in mass by a factor of 2433; where many bodies 2433 times apart "
                  "in mass touch at once, heavy ones may sink into light ones and the crowd may "
                  "gain energy (docs/physics.md, Limits)"}));
    EXPECT_EQ(warnings(R"(
version: 1
video: {duration: 12}
physics: {seed: 20}
bodies:
  - random_polygons: {count: 8, region: [[0, 0], [10, 10]], size: [0.01, 1], speed: 20, respawn_every: 1}
)"),
              (std::vector<std::string>{
                  "s.yaml:6:85: warning: bodies[0].random_polygons.speed: after the respawn at t "
                  "= 1 s, 20 m/s: crowds of this scene's bodies are measured to stay apart up to "
                  "6.042 m/s at 480 Hz (0.1333 radii of the smallest moving body, 0.0944630364734"
                  "9878 m, per physics step for masses differing by a factor of 225.3); where sev"
                  "eral bodies this fast meet at once they may overlap; physics.rate 1589 or more"
                  " keeps them apart (docs/physics.md, Limits)"}));
}

// A clip the caller makes longer than video.duration (--duration) gets its respawns to the
// end; one beyond the limit on duration, which the caller refuses, only the file's.
TEST(Bodies, RespawnsCoverTheClipLengthTheCallerGives) {
    const std::string yaml = R"(
version: 1
video: {duration: 4}
bodies:
  - random_polygons: {count: 2, region: [[0, 0], [5, 5]], size: 0.3, respawn_every: 3}
)";
    const auto times = [](const LoadResult& r) {
        std::vector<double> at;
        for (const Respawn& respawn : r.scene.respawns) at.push_back(respawn.at);
        return at;
    };
    const LoadResult file = load_scene_text(yaml, "s.yaml");
    const LoadResult longer = load_scene_text(yaml, "s.yaml", {}, 10.0);
    const LoadResult refused = load_scene_text(yaml, "s.yaml", {}, 1e9);
    ASSERT_TRUE(file.ok() && longer.ok() && refused.ok());
    EXPECT_EQ(times(file), (std::vector<double>{3}));
    EXPECT_EQ(times(longer), (std::vector<double>{3, 6, 9}));
    EXPECT_EQ(longer.scene.video.duration, 4.0);   // the caller sets it
    EXPECT_EQ(times(refused), (std::vector<double>{3}));
    // The same draws: the first respawn does not depend on the clip's length.
    EXPECT_EQ(longer.scene.respawns[0].bodies[1].position,
              file.scene.respawns[0].bodies[1].position);
}

TEST(Bodies, ThrowsNameBodiesWithBodyOrDisc) {
    const Scene s = load_ok(R"(
version: 1
discs:
  - {position: [0, 0], radius: 0.5}
bodies:
  - {id: crate, box: [1, 1], position: [3, 0]}
throws:
  - {body: crate, at: 1, velocity: [1, 0]}
  - {disc: crate, at: 2, velocity: [0, 1]}
)");
    ASSERT_EQ(s.throws.size(), 2u);
    EXPECT_EQ(s.throws[0].body, 1u);
    EXPECT_EQ(s.throws[1].body, 1u);
}

TEST(Bodies, RespawnsCountAgainstTheLimitOnBodies) {
    Limits limits;
    limits.bodies = 100;
    const LoadResult r = load_scene_text(R"(
version: 1
video: {duration: 10}
bodies:
  - random_polygons: {count: 30, region: [[0, 0], [10, 10]], size: 0.2, respawn_every: 2}
)", "s.yaml", limits);
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_EQ(r.diagnostics[0].to_string(),
              "s.yaml:5:73: bodies[0].respawn_every: respawning every 2 s brings the scene to 120 "
              "bodies over the clip; the limit is 100 (raise it with --max-bodies)");
}

}  // namespace
}  // namespace discreel::scene

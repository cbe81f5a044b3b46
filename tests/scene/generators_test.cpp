// The grid and random generators: counts, ids, placement, determinism.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "random.hpp"
#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using testing::load_ok;

std::string random_scene(int seed, int count = 150) {
    return "version: 1\nphysics: {seed: " + std::to_string(seed) + R"(}
discs:
  - {id: big, position: [5, 5], radius: 1.5}
  - random:
      count: )" + std::to_string(count) + R"(
      region: [[0, 0], [10, 10]]
      radius: [0.1, 0.3]
      speed: [1, 2]
)";
}

TEST(Grid, PlacesColumnsAlongXAndRowsAlongYWithEveryDiscKey) {
    const Scene s = load_ok(R"(version: 1
discs:
  - {position: [-5, -5], radius: 0.1}
  - id: pegs
    static: true
    mass: 2
    velocity: [1, 2]
    restitution: 0.3
    color: "#102030"
    grid:
      origin: [1, 2]
      count: [3, 2]
      spacing: [0.5, 0.25]
      radius: 0.1
)");
    ASSERT_EQ(s.bodies.size(), 7u);
    const Vec2 expected[] = {{1, 2}, {1.5, 2}, {2, 2}, {1, 2.25}, {1.5, 2.25}, {2, 2.25}};
    for (std::size_t k = 0; k < 6; ++k) {
        const Body& d = s.bodies[1 + k];
        EXPECT_EQ(d.id, "pegs." + std::to_string(k));
        EXPECT_EQ(d.position, expected[k]) << k;
        EXPECT_EQ(d.radius, 0.1);
        EXPECT_TRUE(d.is_static);
        EXPECT_EQ(d.mass, 2);
        EXPECT_EQ(d.velocity, (Vec2{1, 2}));
        EXPECT_EQ(d.restitution, 0.3);
        EXPECT_EQ(d.color, (Color{0x10, 0x20, 0x30, 0xff}));
    }
}

// docs/scene-format.md writes the shared keys inside `grid:`; beside it works the same.
TEST(Grid, SharedDiscKeysMayBeWrittenInsideTheGenerator) {
    const Scene s = load_ok(R"(version: 1
discs:
  - grid:
      id: pegs
      count: [2, 1]
      radius: 0.1
      static: true
      velocity: [1, 2]
    restitution: 0.3
  - random:
      id: dust
      count: 3
      region: [[5, 5], [8, 8]]
      radius: 0.1
      density: 2
)");
    ASSERT_EQ(s.bodies.size(), 5u);
    EXPECT_EQ(s.bodies[1].id, "pegs.1");
    EXPECT_TRUE(s.bodies[1].is_static);
    EXPECT_EQ(s.bodies[1].velocity, (Vec2{1, 2}));
    EXPECT_EQ(s.bodies[1].restitution, 0.3);
    EXPECT_EQ(s.bodies[4].id, "dust.2");
    EXPECT_DOUBLE_EQ(s.bodies[4].mass, 2 * std::numbers::pi * 0.01);
}

TEST(Grid, IdsUseTheEntryIndexAndDefaultSpacingJustTouches) {
    const Scene s = load_ok(R"(version: 1
discs:
  - {position: [-5, -5], radius: 0.1}
  - {position: [-5, -3], radius: 0.1}
  - grid: {count: [4, 1], radius: 0.25}
)");
    ASSERT_EQ(s.bodies.size(), 6u);
    EXPECT_EQ(s.bodies[2].id, "2.0");
    EXPECT_EQ(s.bodies[5].id, "2.3");
    EXPECT_EQ(s.bodies[2].position, (Vec2{0, 0}));  // origin defaults to [0, 0]
    EXPECT_EQ(s.bodies[5].position, (Vec2{1.5, 0}));
    // Colours without `colors` come from the palette by disc index, like single discs.
    EXPECT_NE(s.bodies[2].color, s.bodies[3].color);
}

TEST(Grid, JitterIsBoundedAndFollowsTheSeed) {
    const auto positions = [](int seed) {
        const Scene s = load_ok("version: 1\nphysics: {seed: " + std::to_string(seed) +
                                "}\ndiscs:\n  - grid: {count: [5, 5], spacing: [1, 1], "
                                "radius: 0.2, jitter: 0.05}\n");
        std::vector<Vec2> p;
        for (const Body& d : s.bodies) p.push_back(d.position);
        return p;
    };
    const auto a = positions(7), again = positions(7), other = positions(8);
    ASSERT_EQ(a.size(), 25u);
    EXPECT_EQ(a, again);
    EXPECT_NE(a, other);
    bool any_moved = false;
    for (int k = 0; k < 25; ++k) {
        const double dx = a[k].x - k % 5, dy = a[k].y - k / 5;
        EXPECT_LE(std::abs(dx), 0.05);
        EXPECT_LE(std::abs(dy), 0.05);
        any_moved = any_moved || dx != 0 || dy != 0;
    }
    EXPECT_TRUE(any_moved);
}

TEST(Random, PlacesEveryDiscInsideTheRegionWithoutOverlap) {
    const Scene s = load_ok(random_scene(1));
    ASSERT_EQ(s.bodies.size(), 151u);
    for (std::size_t i = 1; i < s.bodies.size(); ++i) {
        const Body& d = s.bodies[i];
        EXPECT_EQ(d.id, "1." + std::to_string(i - 1));
        EXPECT_GE(d.radius, 0.1);
        EXPECT_LE(d.radius, 0.3);
        EXPECT_GE(d.position.x - d.radius, 0.0);
        EXPECT_LE(d.position.x + d.radius, 10.0);
        EXPECT_GE(d.position.y - d.radius, 0.0);
        EXPECT_LE(d.position.y + d.radius, 10.0);
        const double speed = std::hypot(d.velocity.x, d.velocity.y);
        EXPECT_GE(speed, 1.0 - 1e-12);
        EXPECT_LE(speed, 2.0 + 1e-12);
        EXPECT_DOUBLE_EQ(d.mass, std::numbers::pi * d.radius * d.radius);
    }
    // Every pair, the explicit disc included: none may overlap.
    for (std::size_t i = 0; i < s.bodies.size(); ++i)
        for (std::size_t j = i + 1; j < s.bodies.size(); ++j) {
            const double gap = std::hypot(s.bodies[i].position.x - s.bodies[j].position.x,
                                          s.bodies[i].position.y - s.bodies[j].position.y) -
                               s.bodies[i].radius - s.bodies[j].radius;
            EXPECT_GE(gap, 0.0) << s.bodies[i].id << " and " << s.bodies[j].id;
        }
}

TEST(Random, TheSameSeedGivesTheSameSceneAndAnotherSeedAnother) {
    const Scene a = load_ok(random_scene(42));
    const Scene b = load_ok(random_scene(42));
    const Scene c = load_ok(random_scene(43));
    ASSERT_EQ(a.bodies.size(), b.bodies.size());
    ASSERT_EQ(a.bodies.size(), c.bodies.size());
    bool differs = false;
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        EXPECT_EQ(a.bodies[i].position, b.bodies[i].position);
        EXPECT_EQ(a.bodies[i].velocity, b.bodies[i].velocity);
        EXPECT_EQ(a.bodies[i].radius, b.bodies[i].radius);
        differs = differs || a.bodies[i].position != c.bodies[i].position;
    }
    EXPECT_TRUE(differs);
}

TEST(Random, TheRandomStreamIsPinnedAcrossPlatforms) {
    // xoshiro256** seeded by splitmix64: this value must never change, or every scene with a
    // generator changes shape. Computed with an independent Python transcription of the
    // reference algorithms (state words from splitmix64 of seed ^ stream * 0xd1b54a32d192ed03).
    constexpr std::uint64_t pinned_first_value = 0xb3f2af6d0fc710c5ull;
    detail::Rng rng(1, 0);
    const std::uint64_t first = rng.next();
    detail::Rng same(1, 0);
    EXPECT_EQ(same.next(), first);
    detail::Rng other_stream(1, 1);
    EXPECT_NE(other_stream.next(), first);
    EXPECT_EQ(first, pinned_first_value);
}

TEST(Random, UnitValuesStayInTheHalfOpenInterval) {
    detail::Rng rng(123, 4);
    double lo = 1, hi = 0;
    for (int i = 0; i < 10000; ++i) {
        const double u = rng.unit();
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        lo = std::min(lo, u);
        hi = std::max(hi, u);
    }
    EXPECT_LT(lo, 0.01);  // 10 000 draws cover the interval: the chance of missing is 1e-44
    EXPECT_GT(hi, 0.99);
}

TEST(Generators, TenThousandDiscsLoad) {
    const Scene s = load_ok("version: 1\ndiscs:\n  - grid: {count: [100, 100], radius: 0.05}\n"
                            "  - random: {count: 1000, region: [[20, 0], [40, 20]], radius: 0.1}\n");
    EXPECT_EQ(s.bodies.size(), 11000u);
}

}  // namespace
}  // namespace discreel::scene

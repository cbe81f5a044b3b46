// White-box: the broad phase's pair list (broad_phase.hpp) against the O(N^2) list of the pairs
// it promises, in each of its ways of finding them: grid cells numbered row by row (the discs
// close together), hashed cells (spread far apart, so that cells share buckets), and the plain
// scan that pairs discs much larger or faster than the rest.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "broad_phase.hpp"
#include "discreel/physics.hpp"
#include "geometry.hpp"
#include "scenes.hpp"

namespace discreel::physics::detail {
namespace {

constexpr double dt = 1.0 / 480;  // s, one step
constexpr double gravity = 9.81;  // m/s^2

using Pair = std::pair<std::uint32_t, std::uint32_t>;

// Discs first, then one fixed body per wall feature, as World lays them out.
struct Scene {
    std::vector<Body> bodies;
    std::size_t disc_count = 0;
    std::vector<Feature> features;

    void add_disc(V2 x, V2 v, double radius, Motion motion) {
        Body b;
        b.x = x;
        b.radius = radius;
        b.motion = motion;
        if (motion != Motion::fixed) b.v = v;
        if (motion == Motion::dynamic) {
            b.mass = 1.0;
            b.inv_mass = 1.0;
        }
        bodies.push_back(b);
        ++disc_count;
    }
    void add_walls(const std::vector<WallDef>& walls) {
        features = features_of(walls);
        bodies.resize(disc_count + features.size());
    }
};

// Mostly falling discs, some pegs (fixed) and some held (moving, infinitely heavy).
Motion random_motion(testing::Rng& rng) {
    const double u = rng.uniform(0, 1);
    return u < 0.1 ? Motion::fixed : u < 0.15 ? Motion::held : Motion::dynamic;
}

// What the broad phase promises, by brute force with its own margins: two discs, not both
// fixed, whose discs grown by their margins overlap or touch; a moving disc and a wall feature
// that applies to it no farther away than its margin. In (a, b) order.
std::vector<Pair> brute_force_pairs(const Scene& s, const BroadPhase& broad) {
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < s.disc_count; ++i) {
        const Body& a = s.bodies[i];
        for (std::size_t j = i + 1; j < s.disc_count; ++j) {
            const Body& b = s.bodies[j];
            if (!a.moves() && !b.moves()) continue;
            const double reach = a.radius + broad.margin(i) + (b.radius + broad.margin(j));
            if ((a.x - b.x).squaredNorm() <= reach * reach) {
                pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
            }
        }
        if (!a.moves()) continue;
        for (std::size_t f = 0; f < s.features.size(); ++f) {
            if (feature_applies(s.features[f], a.x) &&
                disc_feature(a.x, a.radius, s.features[f]).gap <= broad.margin(i)) {
                pairs.emplace_back(static_cast<std::uint32_t>(i),
                                   static_cast<std::uint32_t>(s.disc_count + f));
            }
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

std::vector<Pair> listed_pairs(const std::vector<Contact>& contacts) {
    std::vector<Pair> pairs;
    for (const Contact& c : contacts) pairs.emplace_back(c.a, c.b);
    return pairs;
}

// Rebuilds the list of s and compares it with brute force, pair for pair and in order.
void expect_brute_force_pairs(const Scene& s, BroadPhase& broad, std::vector<Contact>& contacts,
                              bool hashed) {
    ASSERT_TRUE(broad.update(s.bodies, s.disc_count, s.features, dt, gravity, contacts, false));
    EXPECT_EQ(broad.hashed(), hashed);
    const std::vector<Pair> expected = brute_force_pairs(s, broad);
    EXPECT_EQ(listed_pairs(contacts), expected);
    // An empty list would match an empty brute force too.
    EXPECT_GT(expected.size(), s.disc_count / 2);
}

// A crowd in a 20 m box with a slanted segment: radii 0.1 to 0.3 m, up to 3 m/s.
Scene crowd(std::uint64_t seed) {
    Scene s;
    testing::Rng rng(seed);
    for (int k = 0; k < 1500; ++k) {
        const V2 x(rng.uniform(0, 20), rng.uniform(0, 20));
        const V2 v(rng.uniform(-3, 3), rng.uniform(-3, 3));
        const double radius = rng.uniform(0.1, 0.3);
        s.add_disc(x, v, radius, random_motion(rng));
    }
    s.add_walls({testing::box({0, 0}, {20, 20}), testing::segment({2, 15}, {18, 11}, 0.1)});
    return s;
}

TEST(BroadPhasePairs, CrowdInOneBoxMatchesBruteForceWithCellsRowByRow) {
    for (const std::uint64_t seed : {1, 2, 3}) {
        SCOPED_TRACE(seed);
        const Scene s = crowd(seed);
        BroadPhase broad;
        std::vector<Contact> contacts;
        expect_brute_force_pairs(s, broad, contacts, false);
    }
}

TEST(BroadPhasePairs, BeadsAmongPegsMatchBruteForce) {
    // A Galton board's layout: a lattice of pegs (fixed), as many beads falling among them,
    // and a few held. Pegs share cells with pegs and beads: a peg must meet the beads of its
    // own and the neighbouring cells, and never another peg.
    Scene s;
    testing::Rng rng(21);
    for (int row = 0; row < 20; ++row) {
        for (int col = 0; col < 30; ++col) {
            s.add_disc({0.5 + 0.3 * col + 0.15 * (row % 2), 1.0 + 0.3 * row}, V2::Zero(), 0.08,
                       Motion::fixed);
        }
    }
    for (int k = 0; k < 600; ++k) {
        const V2 x(rng.uniform(0.3, 9.5), rng.uniform(0.8, 7.0));
        const V2 v(rng.uniform(-1, 1), rng.uniform(-4, 0));
        s.add_disc(x, v, rng.uniform(0.05, 0.08), k % 50 == 0 ? Motion::held : Motion::dynamic);
    }
    s.add_walls({testing::box({0, 0}, {10, 8})});
    BroadPhase broad;
    std::vector<Contact> contacts;
    expect_brute_force_pairs(s, broad, contacts, false);
    std::size_t peg_bead = 0;
    for (const Contact& c : contacts) peg_bead += c.a < 600 && c.b >= 600 && c.b < s.disc_count;
    EXPECT_GT(peg_bead, 100u);
}

TEST(BroadPhasePairs, ClumpsFarApartMatchBruteForceWithHashedCells) {
    // 400 clumps of three to five discs, 10 km apart at most: far more cells than the table
    // has buckets, so they are hashed and many buckets hold cells of several clumps.
    Scene s;
    testing::Rng rng(11);
    for (int clump = 0; clump < 400; ++clump) {
        const V2 centre(rng.uniform(-5000, 5000), rng.uniform(-5000, 5000));
        const int size = 3 + clump % 3;
        for (int k = 0; k < size; ++k) {
            const V2 x = centre + V2(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
            const V2 v(rng.uniform(-3, 3), rng.uniform(-3, 3));
            s.add_disc(x, v, rng.uniform(0.1, 0.3), random_motion(rng));
        }
    }
    s.add_walls({testing::segment({-4000, 0}, {4000, 10}, 0.1)});
    BroadPhase broad;
    std::vector<Contact> contacts;
    expect_brute_force_pairs(s, broad, contacts, true);
}

TEST(BroadPhasePairs, OversizedDiscsAreScannedAgainstAll) {
    // Large discs and fast ones (a wide margin) would force huge cells on everyone: they are
    // paired by a plain scan, with each other and with the crowd.
    Scene s = crowd(4);
    s.bodies.resize(s.disc_count);  // the walls' bodies: added again after the new discs
    testing::Rng rng(5);
    for (int k = 0; k < 6; ++k) {
        const V2 x(rng.uniform(2, 18), rng.uniform(2, 18));
        s.add_disc(x, V2(0.5, 0), 2.0 + k * 0.3, k % 3 == 0 ? Motion::fixed : Motion::dynamic);
    }
    s.add_disc({10, 10}, {900, 0}, 0.2, Motion::dynamic);  // crosses the box in a few steps
    s.add_disc({10.5, 10}, {0, -900}, 0.2, Motion::held);
    s.add_walls({testing::box({0, 0}, {20, 20}), testing::segment({2, 15}, {18, 11}, 0.1)});
    BroadPhase broad;
    std::vector<Contact> contacts;
    expect_brute_force_pairs(s, broad, contacts, false);
    // The large ones' margins are what sends them to the scan: check that some pairs come
    // from it (two oversized discs, and an oversized one with the crowd).
    const std::size_t first_big = s.disc_count - 8;  // the last discs; a < b in every pair
    std::size_t big_big = 0, big_crowd = 0;
    for (const Contact& c : contacts) {
        const bool a_big = c.a >= first_big, b_big = c.b >= first_big && c.b < s.disc_count;
        big_big += a_big && b_big;
        big_crowd += !a_big && b_big;
    }
    EXPECT_GT(big_big, 0u);
    EXPECT_GT(big_crowd, 100u);
}

TEST(BroadPhasePairs, ListAfterTheDiscsMovedMatchesBruteForceAndKeepsSurvivorsHistory) {
    Scene s = crowd(6);
    BroadPhase broad;
    std::vector<Contact> contacts;
    expect_brute_force_pairs(s, broad, contacts, false);
    for (Contact& c : contacts) c.normal_impulse = 1.0 + c.a + 1e-6 * c.b;  // a mark per pair
    for (std::size_t i = 0; i < s.disc_count; ++i) {
        Body& b = s.bodies[i];
        if (b.moves()) b.x += b.v * 0.05;
    }
    expect_brute_force_pairs(s, broad, contacts, false);
    std::size_t kept = 0, fresh = 0;
    for (const Contact& c : contacts) {
        if (c.normal_impulse == 0.0) {
            ++fresh;
        } else {
            ASSERT_EQ(c.normal_impulse, 1.0 + c.a + 1e-6 * c.b) << c.a << " " << c.b;
            ++kept;
        }
    }
    EXPECT_GT(kept, fresh);
    EXPECT_GT(fresh, 0u);
}

}  // namespace
}  // namespace discreel::physics::detail

// White-box: the manifold solver's broad phase (fat_pairs.hpp) against the O(N^2) list of the
// pairs it promises (two bodies, not both immovable, whose fattened boxes overlap or touch), in
// (a, b) order: boxes of many sizes and shapes, boxes that only touch, walls' long boxes, and
// bodies far from the origin; and when the list holds and when it is rebuilt.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "fat_pairs.hpp"
#include "scenes.hpp"

namespace discreel::physics::detail {
namespace {

struct Layout {
    std::vector<Box> needed;
    std::vector<double> margin;
    std::vector<unsigned char> movable;

    void add(double x, double y, double half_w, double half_h, double m, bool moves) {
        needed.push_back({x - half_w, y - half_h, x + half_w, y + half_h});
        margin.push_back(m);
        movable.push_back(moves ? 1 : 0);
    }
};

std::vector<std::uint64_t> brute_force(const Layout& l) {
    std::vector<std::uint64_t> pairs;
    const auto fat = [&](std::size_t i) {
        const Box& b = l.needed[i];
        const double m = l.margin[i];
        return Box{b[0] - m, b[1] - m, b[2] + m, b[3] + m};
    };
    for (std::size_t i = 0; i < l.needed.size(); ++i) {
        for (std::size_t j = i + 1; j < l.needed.size(); ++j) {
            if (!l.movable[i] && !l.movable[j]) continue;
            if (boxes_overlap(fat(i), fat(j))) pairs.push_back(i << 32 | j);
        }
    }
    return pairs;
}

// A pile in a 12 m box: boxes from 2 cm to 1 m on a side, thin ones among them, the four
// walls' slabs (immovable, 12 m long: paired by the plain scan), some fixed pegs.
Layout pile(std::uint64_t seed, V2 origin) {
    Layout l;
    testing::Rng rng(seed);
    for (int k = 0; k < 1200; ++k) {
        const double half_w = rng.uniform(0.01, 0.5);
        const double half_h = k % 5 == 0 ? 0.01 : rng.uniform(0.01, 0.5);
        const bool moves = rng.uniform(0, 1) > 0.05;
        l.add(origin.x() + rng.uniform(0, 12), origin.y() + rng.uniform(0, 12), half_w, half_h,
              rng.uniform(0, 0.1), moves);
    }
    l.add(origin.x() + 6, origin.y() - 0.5, 7, 0.5, 0.0, false);
    l.add(origin.x() + 6, origin.y() + 12.5, 7, 0.5, 0.0, false);
    l.add(origin.x() - 0.5, origin.y() + 6, 0.5, 7, 0.0, false);
    l.add(origin.x() + 12.5, origin.y() + 6, 0.5, 7, 0.0, false);
    return l;
}

TEST(FatPairs, APileMatchesBruteForce) {
    for (const std::uint64_t seed : {1, 2, 3}) {
        SCOPED_TRACE(seed);
        const Layout l = pile(seed, V2::Zero());
        FatPairs fat;
        std::vector<std::uint64_t> pairs;
        ASSERT_TRUE(fat.update(l.needed, l.margin, l.movable, pairs));
        const std::vector<std::uint64_t> expected = brute_force(l);
        EXPECT_EQ(pairs, expected);
        EXPECT_GT(expected.size(), l.needed.size() / 2);   // not two empty lists
    }
}

TEST(FatPairs, FarFromTheOriginMatchesBruteForce) {
    // Centres a million metres out, boxes of centimetres: the rounding of the circles the
    // search uses is far larger there than near the origin.
    const Layout l = pile(4, V2(1e6, -3e6));
    FatPairs fat;
    std::vector<std::uint64_t> pairs;
    ASSERT_TRUE(fat.update(l.needed, l.margin, l.movable, pairs));
    EXPECT_EQ(pairs, brute_force(l));
}

TEST(FatPairs, BoxesThatOnlyTouchArePaired) {
    // Corner to corner, edge to edge, and one just apart: exact coordinates, no margin.
    Layout l;
    l.add(0.5, 0.5, 0.5, 0.5, 0.0, true);
    l.add(1.5, 1.5, 0.5, 0.5, 0.0, true);    // touches the first at the corner (1, 1)
    l.add(2.25, 1.5, 0.25, 0.5, 0.0, true);  // shares the edge x = 2 with the second
    l.add(3.5, 1.5, 0.5, 0.5, 0.0, true);    // 0.5 m from the third
    FatPairs fat;
    std::vector<std::uint64_t> pairs;
    ASSERT_TRUE(fat.update(l.needed, l.margin, l.movable, pairs));
    EXPECT_EQ(pairs, (std::vector<std::uint64_t>{0ull << 32 | 1, 1ull << 32 | 2}));
}

TEST(FatPairs, TheListHoldsWhileEveryBoxStaysInsideItsFatOne) {
    Layout l = pile(5, V2::Zero());
    FatPairs fat;
    std::vector<std::uint64_t> pairs;
    ASSERT_TRUE(fat.update(l.needed, l.margin, l.movable, pairs));
    const std::vector<std::uint64_t> built = pairs;
    // Each box moved by half its margin: inside its fat box still, so the list is kept.
    for (std::size_t i = 0; i < l.needed.size(); ++i) {
        for (double& side : l.needed[i]) side += 0.5 * l.margin[i];
    }
    EXPECT_FALSE(fat.update(l.needed, l.margin, l.movable, pairs));
    EXPECT_EQ(pairs, built);
    EXPECT_EQ(fat.rebuilds(), 1u);
    // One box out of its fat box, or one body that stops being movable: rebuilt, and right.
    l.needed[7][2] += 1.0;
    EXPECT_TRUE(fat.update(l.needed, l.margin, l.movable, pairs));
    EXPECT_EQ(pairs, brute_force(l));
    l.movable[8] = l.movable[8] != 0 ? 0 : 1;
    EXPECT_TRUE(fat.update(l.needed, l.margin, l.movable, pairs));
    EXPECT_EQ(pairs, brute_force(l));
    EXPECT_EQ(fat.rebuilds(), 3u);
}

}  // namespace
}  // namespace discreel::physics::detail

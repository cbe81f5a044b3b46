// White-box: the broad phase's radix sort of pair keys (broad_phase.hpp) against std::sort, on
// random keys (a fixed seed) for body counts that take one to six passes of its 11-bit digits.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "broad_phase.hpp"

namespace discreel::physics::detail {
namespace {

// `count` keys a << 32 | b with a and b uniform below `below` (std::mt19937_64's output is the
// same everywhere; its distributions' are not, hence the modulo).
std::vector<std::uint64_t> random_keys(std::size_t count, std::uint64_t below,
                                       std::mt19937_64& rng) {
    std::vector<std::uint64_t> keys(count);
    for (std::uint64_t& key : keys) {
        const std::uint64_t a = rng() % below;
        key = a << 32 | rng() % below;
    }
    return keys;
}

void expect_sorted_like_std_sort(std::vector<std::uint64_t> keys, std::size_t body_count,
                                 std::vector<std::uint64_t>& scratch,
                                 std::vector<std::uint32_t>& count) {
    std::vector<std::uint64_t> expected = keys;
    std::sort(expected.begin(), expected.end());
    sort_pair_keys(keys, body_count, scratch, count);
    ASSERT_EQ(keys, expected) << "body count " << body_count;
}

TEST(RadixSort, SortsRandomKeysLikeStdSortForEveryPassCount) {
    std::mt19937_64 rng(20240601);
    std::vector<std::uint64_t> scratch;  // reused across sorts of different sizes, as it is
    std::vector<std::uint32_t> count;
    // Body counts needing 1 to 32 bits per index: one pass (2 bits a key) up to six (64 bits);
    // 2^11 and 2^22 are where a pass is added.
    for (const std::uint64_t bodies :
         {1ull, 2ull, 3ull, 100ull, 1023ull, 1024ull, 2047ull, 2048ull, 70'000ull,
          (1ull << 22) - 1, 1ull << 22, 1ull << 31, (1ull << 32) - 1}) {
        for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{2},
                                    std::size_t{777}, std::size_t{20'000}}) {
            SCOPED_TRACE(n);
            expect_sorted_like_std_sort(random_keys(n, bodies, rng), bodies, scratch, count);
        }
    }
}

TEST(RadixSort, KeepsEveryCopyOfRepeatedKeys) {
    std::mt19937_64 rng(7);
    std::vector<std::uint64_t> scratch;
    std::vector<std::uint32_t> count;
    // 5 000 keys from 9 distinct ones: each comes out as many times as it went in.
    expect_sorted_like_std_sort(random_keys(5'000, 3, rng), 3, scratch, count);
    expect_sorted_like_std_sort(random_keys(5'000, 3, rng), 50'000, scratch, count);
}

TEST(RadixSort, BodyCountsBeyondThirtyTwoBitsSortByTheWholeKey) {
    // Indices never exceed 32 bits, however many bodies are claimed.
    std::mt19937_64 rng(3);
    std::vector<std::uint64_t> scratch;
    std::vector<std::uint32_t> count;
    expect_sorted_like_std_sort(random_keys(10'000, 1ull << 32, rng), std::size_t{1} << 40,
                                scratch, count);
}

}  // namespace
}  // namespace discreel::physics::detail

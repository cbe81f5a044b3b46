#pragma once
// The benches' seeded numbers: splitmix64, identical on every platform, so a layout drawn from
// a seed is the same scene in every bench (body_bench, physics_bench and box2d_bench build the
// same bodies from it).
#include <cstdint>

namespace discreel::bench {

// The next number of the sequence `state` is at, uniform in [lo, hi).
inline double uniform(std::uint64_t& state, double lo, double hi) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
}

}  // namespace discreel::bench

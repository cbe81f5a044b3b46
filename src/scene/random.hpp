#pragma once
// The scene's own random numbers: xoshiro256** seeded through splitmix64. Written out here
// rather than taken from <random> because the standard distributions are implementation-defined:
// the same seed must give the same scene with every compiler and library.
#include <cstdint>

namespace discreel::scene::detail {

class Rng {
public:
    // One independent stream per (seed, stream): each generator in a scene draws from its own,
    // so editing one generator does not reshuffle the others.
    Rng(std::uint64_t seed, std::uint64_t stream) {
        std::uint64_t mix = seed ^ (stream * 0xd1b54a32d192ed03ull);
        for (auto& word : state_) word = splitmix64(mix);
    }

    std::uint64_t next() {
        const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
        const std::uint64_t t = state_[1] << 17;
        state_[2] ^= state_[0];
        state_[3] ^= state_[1];
        state_[1] ^= state_[2];
        state_[0] ^= state_[3];
        state_[2] ^= t;
        state_[3] = rotl(state_[3], 45);
        return result;
    }

    // Uniform in [0, 1): the top 53 bits, exactly representable.
    double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

    // Uniform in [lo, hi) (exactly lo when lo == hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

    static std::uint64_t splitmix64(std::uint64_t& x) {
        std::uint64_t z = (x += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }

    std::uint64_t state_[4];
};

}  // namespace discreel::scene::detail

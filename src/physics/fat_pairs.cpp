#include "fat_pairs.hpp"

#include <algorithm>

#include "body_solver.hpp"

namespace discreel::physics::detail {

bool FatPairs::holds(std::span<const Box> needed, std::span<const unsigned char> movable) const {
    if (fat_.size() != needed.size()) return false;
    for (std::size_t i = 0; i < needed.size(); ++i) {
        const Box& n = needed[i];
        const Box& f = fat_[i];
        if (n[0] < f[0] || n[1] < f[1] || n[2] > f[2] || n[3] > f[3]) return false;
        if (movable[i] != movable_[i]) return false;
    }
    return true;
}

bool FatPairs::update(std::span<const Box> needed, std::span<const double> margin,
                      std::span<const unsigned char> movable, std::vector<std::uint64_t>& pairs) {
    if (holds(needed, movable)) return false;
    ++rebuilds_;
    const std::size_t n = needed.size();
    fat_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Box& b = needed[i];
        const double m = margin[i];
        fat_[i] = {b[0] - m, b[1] - m, b[2] + m, b[3] + m};
    }
    movable_.assign(movable.begin(), movable.end());
    pairs.clear();
    for_each_overlapping_pair(fat_, order_, [&](std::uint32_t i, std::uint32_t j) {
        if (!movable[i] && !movable[j]) return;
        const std::uint64_t a = std::min(i, j), b = std::max(i, j);
        pairs.push_back(a << 32 | b);
    });
    std::sort(pairs.begin(), pairs.end());
    return true;
}

}  // namespace discreel::physics::detail

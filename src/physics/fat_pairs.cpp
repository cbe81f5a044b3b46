#include "fat_pairs.hpp"

#include <cmath>

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
    // A body whose state stopped being finite in one of the step's substeps (World stops the
    // world at the step's end) would reach the grid's cells, whose conversion of a NaN is
    // undefined: the list is kept as it was.
    for (const Box& b : needed) {
        if (!std::isfinite(b[0] + b[1] + b[2] + b[3])) return false;
    }
    ++rebuilds_;
    const std::size_t n = needed.size();
    fat_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Box& b = needed[i];
        const double m = margin[i];
        fat_[i] = {b[0] - m, b[1] - m, b[2] + m, b[3] + m};
    }
    movable_.assign(movable.begin(), movable.end());
    // The grid search (grid_pairs.hpp) over circles around the fat boxes finds every pair
    // whose boxes can overlap; the boxes themselves decide. Each circle is grown by a trillionth
    // of its size and of its distance from the origin, more than the rounding of its centre and
    // of the search's distances, so that boxes that only touch are not lost to it.
    circles_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Box& f = fat_[i];
        const V2 centre(0.5 * (f[0] + f[2]), 0.5 * (f[1] + f[3]));
        const double half_diagonal = 0.5 * std::hypot(f[2] - f[0], f[3] - f[1]);
        const double slack = 1e-12 * (half_diagonal + std::abs(centre.x()) + std::abs(centre.y()));
        circles_[i] = GridCircle{centre, half_diagonal + slack, movable[i] != 0};
    }
    found_.clear();
    grid_.find(circles_, found_);
    pairs.clear();
    for (const std::uint64_t key : found_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        if (boxes_overlap(fat_[i], fat_[j])) pairs.push_back(key);
    }
    sort_pair_keys(pairs, n, sorted_, digit_count_);
    return true;
}

}  // namespace discreel::physics::detail

#include "fat_pairs.hpp"

#include <algorithm>
#include <array>

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
    // Swept along the axis the moving bodies spread over more, by the variance of their boxes'
    // centres: along x, a tall column of falling bodies is one long run of boxes that overlap
    // in x, each tested against all the others. The list is sorted after, so the axis changes
    // nothing but the work.
    std::array<double, 2> sum{}, square{};
    double count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!movable[i]) continue;
        count += 1;
        for (std::size_t k = 0; k < 2; ++k) {
            const double centre = 0.5 * (fat_[i][k] + fat_[i][k + 2]);
            sum[k] += centre;
            square[k] += centre * centre;
        }
    }
    const auto spread = [&](std::size_t k) {
        return square[k] - sum[k] * sum[k] / std::max(count, 1.0);
    };
    const int axis = spread(1) > spread(0) ? 1 : 0;
    for_each_overlapping_pair(
        fat_, order_,
        [&](std::uint32_t i, std::uint32_t j) {
            if (!movable[i] && !movable[j]) return;
            const std::uint64_t a = std::min(i, j), b = std::max(i, j);
            pairs.push_back(a << 32 | b);
        },
        axis);
    std::sort(pairs.begin(), pairs.end());
    return true;
}

}  // namespace discreel::physics::detail

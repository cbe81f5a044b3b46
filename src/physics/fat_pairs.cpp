#include "fat_pairs.hpp"

#include <algorithm>
#include <array>

namespace discreel::physics::detail {
namespace {

// Calls f(i, j) for every pair of `boxes` (min x, min y, max x, max y) that overlap, i before j
// in the order of their low coordinate along `axis` (0: x, 1: y; ties by index), found by a
// sweep over it. `order` is scratch, left holding the boxes' indices in that order.
template <class F>
void for_each_overlapping_pair(std::span<const Box> boxes, std::vector<std::uint32_t>& order,
                               int axis, F&& f) {
    const std::size_t n = boxes.size();
    const auto lo = static_cast<std::size_t>(axis), hi = lo + 2;
    const std::size_t other_lo = 1 - lo, other_hi = other_lo + 2;
    order.resize(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
        return boxes[i][lo] != boxes[j][lo] ? boxes[i][lo] < boxes[j][lo] : i < j;
    });
    for (std::size_t p = 0; p < n; ++p) {
        const std::uint32_t i = order[p];
        const Box& bi = boxes[i];
        for (std::size_t q = p + 1; q < n && boxes[order[q]][lo] <= bi[hi]; ++q) {
            const std::uint32_t j = order[q];
            const Box& bj = boxes[j];
            if (bj[other_lo] > bi[other_hi] || bi[other_lo] > bj[other_hi]) continue;
            f(i, j);
        }
    }
}

}  // namespace

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
    for_each_overlapping_pair(fat_, order_, axis, [&](std::uint32_t i, std::uint32_t j) {
        if (!movable[i] && !movable[j]) return;
        const std::uint64_t a = std::min(i, j), b = std::max(i, j);
        pairs.push_back(a << 32 | b);
    });
    std::sort(pairs.begin(), pairs.end());
    return true;
}

}  // namespace discreel::physics::detail

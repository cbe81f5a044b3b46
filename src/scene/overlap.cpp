#include "overlap.hpp"

#include <algorithm>
#include <cmath>

namespace discreel::scene::detail {

bool overlapping(const Circle& a, const Circle& b) {
    if (a.is_static && b.is_static) return false;
    const double reach = a.radius + b.radius - overlap_tolerance;
    if (reach <= 0) return false;
    const double dx = a.centre.x - b.centre.x, dy = a.centre.y - b.centre.y;
    return dx * dx + dy * dy < reach * reach;
}

CircleGrid::CircleGrid(double cell_size)
    : cell_size_(std::isfinite(cell_size) && cell_size > 0 ? cell_size : 1.0) {}

CircleGrid::Cell CircleGrid::cell_of(Vec2 p) const {
    // Clamped so that far-away coordinates cannot overflow the conversion; clamped cells only
    // lose speed, never correctness, because neighbours are still compared exactly.
    const auto coordinate = [&](double v) {
        return static_cast<long long>(std::clamp(std::floor(v / cell_size_), -1e15, 1e15));
    };
    return {coordinate(p.x), coordinate(p.y)};
}

void CircleGrid::insert(std::size_t index, const Circle& circle) {
    cells_[cell_of(circle.centre)].emplace_back(index, circle);
}

std::optional<std::size_t> CircleGrid::first_overlap(
    const Circle& circle, const std::function<bool(std::size_t)>& confirm) const {
    const Cell home = cell_of(circle.centre);
    std::optional<std::size_t> first;
    for (long long dx = -1; dx <= 1; ++dx) {
        for (long long dy = -1; dy <= 1; ++dy) {
            const auto cell = cells_.find({home.first + dx, home.second + dy});
            if (cell == cells_.end()) continue;
            for (const auto& [index, other] : cell->second) {
                if (first && index >= *first) break;  // entries are in index order
                if (overlapping(circle, other) && (!confirm || confirm(index))) {
                    first = index;
                    break;
                }
            }
        }
    }
    return first;
}

std::vector<std::pair<std::size_t, std::size_t>> find_overlaps(const std::vector<Circle>& circles,
                                                               const std::vector<bool>& include,
                                                               const ConfirmOverlap& confirm) {
    double largest = 0;
    for (std::size_t i = 0; i < circles.size(); ++i)
        if (include[i]) largest = std::max(largest, circles[i].radius);
    // Static circles live in a grid of their own: they are never compared with each other,
    // so a thousand pegs stacked on one spot cost nothing.
    CircleGrid moving(2 * largest), fixed(2 * largest);
    std::vector<std::pair<std::size_t, std::size_t>> overlaps;
    for (std::size_t i = 0; i < circles.size(); ++i) {
        if (!include[i]) continue;
        const Circle& c = circles[i];
        std::function<bool(std::size_t)> confirm_i;
        if (confirm) confirm_i = [&](std::size_t earlier) { return confirm(i, earlier); };
        std::optional<std::size_t> first = moving.first_overlap(c, confirm_i);
        if (!c.is_static) {
            const auto with_fixed = fixed.first_overlap(c, confirm_i);
            if (with_fixed && (!first || *with_fixed < *first)) first = with_fixed;
        }
        if (first) overlaps.emplace_back(i, *first);
        (c.is_static ? fixed : moving).insert(i, c);
    }
    return overlaps;
}

}  // namespace discreel::scene::detail

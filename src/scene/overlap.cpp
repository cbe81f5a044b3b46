#include "overlap.hpp"

#include <algorithm>
#include <cmath>

namespace discreel::scene::detail {
namespace {

double distance_to_rectangle(Vec2 p, Vec2 lo, Vec2 hi) {
    const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
    const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
    return std::hypot(dx, dy);
}

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
    const double abx = b.x - a.x, aby = b.y - a.y;
    const double length2 = abx * abx + aby * aby;
    const double s =
        length2 > 0 ? std::clamp(((p.x - a.x) * abx + (p.y - a.y) * aby) / length2, 0.0, 1.0)
                    : 0.0;
    return std::hypot(p.x - (a.x + s * abx), p.y - (a.y + s * aby));
}

}  // namespace

bool overlapping(const Circle& a, const Circle& b) {
    if (a.is_static && b.is_static) return false;
    const double reach = a.radius + b.radius - overlap_tolerance;
    if (reach <= 0) return false;
    const double dx = a.centre.x - b.centre.x, dy = a.centre.y - b.centre.y;
    return dx * dx + dy * dy < reach * reach;
}

bool overlaps_wall(const Circle& circle, const Wall& wall) {
    const double r = circle.radius - overlap_tolerance;   // touching is not overlapping
    const Vec2 c = circle.centre;
    if (wall.shape == Wall::Shape::segment)
        return distance_to_segment(c, wall.a, wall.b) < r + wall.thickness / 2;
    const Vec2 lo{std::min(wall.a.x, wall.b.x), std::min(wall.a.y, wall.b.y)};
    const Vec2 hi{std::max(wall.a.x, wall.b.x), std::max(wall.a.y, wall.b.y)};
    if (c.x - r >= lo.x && c.x + r <= hi.x && c.y - r >= lo.y && c.y + r <= hi.y) return false;
    // Outside the inside, the sides reach as far out as the box's larger extent
    // (physics::detail::container_slabs).
    const double depth = std::max(hi.x - lo.x, hi.y - lo.y);
    return distance_to_rectangle(c, {lo.x - depth, lo.y - depth}, {hi.x + depth, hi.y + depth}) < r;
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

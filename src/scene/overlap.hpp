#pragma once
// Which discs overlap: a uniform grid of cells at least one largest-diameter wide, so that a
// disc can only overlap discs in its own and the eight neighbouring cells. Used to check the
// scene at t = 0 and to place random discs, and fast enough for 100 000 discs.
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "discreel/scene.hpp"
#include "discreel/vec2.hpp"

namespace discreel::scene::detail {

struct Circle {
    Vec2 centre;          // metres
    double radius = 0;    // metres
    bool is_static = false;
};

// Closer than this is overlapping; exactly touching is not. The slack absorbs rounding in
// positions computed as origin + k * spacing, where a grid of touching discs is meant.
inline constexpr double overlap_tolerance = 1e-9;  // metres

bool overlapping(const Circle& a, const Circle& b);

// Whether a circle overlaps a wall as physics builds it: a box's sides lie outside its corners
// (its inside is free room), a segment is a capsule of half the wall's thickness.
bool overlaps_wall(const Circle& circle, const Wall& wall);

class CircleGrid {
public:
    // `cell_size` must be at least the largest sum of two radii that will be compared.
    explicit CircleGrid(double cell_size);

    void insert(std::size_t index, const Circle& circle);

    // The lowest index among the inserted circles that overlap `circle` and that `confirm`
    // (when given) accepts: a circle may only bound a shape, which can still be clear. Two
    // static circles never count: fixed pegs may be merged into one obstacle on purpose.
    std::optional<std::size_t> first_overlap(
        const Circle& circle, const std::function<bool(std::size_t)>& confirm = {}) const;

private:
    using Cell = std::pair<long long, long long>;
    Cell cell_of(Vec2 p) const;

    double cell_size_;
    std::map<Cell, std::vector<std::pair<std::size_t, Circle>>> cells_;  // index order per cell
};

// For every circle that overlaps an earlier one: (its index, the earliest such other index).
// `confirm(later, earlier)`, when given, decides a pair whose circles overlap: a shaped body's
// circle only bounds it, and the earliest overlapping circle may belong to a shape that is clear
// while a later one is not.
using ConfirmOverlap = std::function<bool(std::size_t later, std::size_t earlier)>;
std::vector<std::pair<std::size_t, std::size_t>> find_overlaps(const std::vector<Circle>& circles,
                                                               const std::vector<bool>& include,
                                                               const ConfirmOverlap& confirm = {});

}  // namespace discreel::scene::detail

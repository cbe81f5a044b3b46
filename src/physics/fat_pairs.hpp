#pragma once
// The broad phase of bodies of any shape: the pairs whose fattened bounding boxes overlap,
// kept from step to step. Each body's box, grown by what a step needs (its travel and the
// speculative distance), is fattened further by a margin when the list is built; the list
// holds while every body's needed box stays inside its fat box and no body starts or stops
// being movable, so a resting pile rebuilds rarely. A rebuild finds the pairs with the grid
// search the disc solver's broad phase uses (grid_pairs.hpp); pairs come out sorted by (a, b),
// and a pair of bodies no contact can move (walls, pegs, held bodies) is left out.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "grid_pairs.hpp"

namespace discreel::physics::detail {

// lo x, lo y, hi x, hi y, metres.
using Box = std::array<double, 4>;

inline bool boxes_overlap(const Box& p, const Box& q) {
    return p[0] <= q[2] && q[0] <= p[2] && p[1] <= q[3] && q[1] <= p[3];
}

class FatPairs {
public:
    // `needed`: each body's box for the coming step; `margin`: how far it is fattened at a
    // rebuild (metres); `movable`: whether a contact can move it. `pairs` keeps every pair
    // whose fat boxes overlap. True when the list was rebuilt.
    bool update(std::span<const Box> needed, std::span<const double> margin,
                std::span<const unsigned char> movable, std::vector<std::uint64_t>& pairs);
    // The list must be rebuilt at the next update (bodies were replaced).
    void invalidate() { fat_.clear(); }
    std::size_t rebuilds() const { return rebuilds_; }

private:
    bool holds(std::span<const Box> needed, std::span<const unsigned char> movable) const;

    std::vector<Box> fat_;
    std::vector<unsigned char> movable_;   // at the last rebuild
    GridPairs grid_;
    // Scratch: a circle around each fat box, the pairs of circles that overlap, the sort's.
    std::vector<GridCircle> circles_;
    std::vector<std::uint64_t> found_, sorted_;
    std::vector<std::uint32_t> digit_count_;
    std::size_t rebuilds_ = 0;
};

}  // namespace discreel::physics::detail
